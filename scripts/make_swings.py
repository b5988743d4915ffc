#!/usr/bin/python3
"""Slow swings for scripts/quality.sh: meshes bent back and forth at one joint, for popping.

    make_swings.py CASE OUTDIR [--frames N]
    make_swings.py --list

Writes OUTDIR/bind.obj, OUTDIR/patch.txt (plain 0-based face ids) and OUTDIR/frames/
swing.0000.obj .. swing.{N-1}.obj, and prints one line describing the case. Deterministic (no
random numbers): the same inputs give the same bytes. Needs /usr/bin/python3 with numpy.

Every case is one joint of a mesh posed by linear blend skinning (LBS) with smooth weights over
one period of a slow swing, N frames (default 60, the period: frame t is at phase
p = (1 - cos(2 pi t / N)) / 2, 0 -> 1 -> back towards 0):
    bend angle  theta(t) = THETA0 + THETA * p      (about the joint's bend axis)
    twist angle phi(t)   = PHI * sin(2 pi t / N)   (about the child bone, so the twist
                                                    goes one way and back while it bends)
    frame       x' = (1 - w) x + w (j + R(theta, phi) (x - j))
A vertex's weight w is a smoothstep of its position along the child bone, from 0 at BLEND
before the joint to 1 at BLEND after it, and is 0 outside the limb: the limb is the
edge-connected component, holding the case's seed vertex (the limb's far end), of the vertices
within RADIUS of the bone's line and beyond the start of the blend; every other vertex keeps
the bind. The patch (a band round the joint): the faces whose every corner lies within PATCH of
the joint along the bone and within RADIUS of its line, in the connected piece that holds the
limb vertex nearest the joint; the largest edge-connected component of those faces.
THETA0 > 0 keeps every frame away from the bind (a frame at rest is returned unchanged).

Cases (sources are read at run time; nothing is copied into the repository):
  swing-tube    coarse, made here: a tube of 24 x 16 quads (384 vertices) along x, radius
                1 + 0.15 sin, uneven spacing along its length; joint at x = 0, bone +x.
  swing-elbow   body-like: the MakeHuman base mesh's group `body` (faces 0..13377 of
                QUALITY_DATA/obj/makehuman/base.obj, CC0 1.0), left elbow (joint = centre of
                the helper cube `joint-l-elbow`, bone towards `joint-l-hand`, bend axis
                perpendicular to upper and lower arm). The OBJ is the whole file's `v` lines
                and the body's faces (helpers left out).
  swing-finger  finger-like: the same body's left middle finger, bent at its second joint
                (`joint-l-finger-3-2`, bone towards `joint-l-finger-3-3`).
  swing-hand    hand-like: CGAL's hand.off (a fist, 1197 vertices; Debian libcgal-demo
                5.5.1-2, /usr/share/doc/libcgal-dev/data.tar.gz, data/meshes/hand.off; CGAL's
                data files carry no notice of their own and the Debian copyright file puts
                such files under CC0 1.0), bent at the wrist (z = -0.25, bone +z).
  swing-cesium  a real skin: CesiumMan.glb (QUALITY_DATA/gltf, CC-BY 4.0, Cesium) welded as
                `quality.py gltf-bind` welds it, posed by its own skin and weights (nodes at
                their stored transforms = the bind), the left elbow's subtree
                (Skeleton_arm_joint_L__3_) turned by the swing about the elbow; the limb
                weights below are not used here (the patch only).
  swing-camel   quadruped-like: CGAL's camel.off (9770 vertices; same package and terms),
                the front left leg swung at its knee (bone -y).
Source locations: QUALITY_DATA (default /work/shared/data) for MakeHuman; CGAL_DATA (default
/usr/share/doc/libcgal-dev/data.tar.gz, installed by `scripts/deps.sh libcgal-demo`) for hand and
camel.
"""
import argparse
import math
import os
import sys
import tarfile

import numpy as np

DATA = os.environ.get("QUALITY_DATA", "/work/shared/data")
CGAL_DATA = os.environ.get("CGAL_DATA", "/usr/share/doc/libcgal-dev/data.tar.gz")


# ---------------------------------------------------------------- reading sources

def read_obj_groups(path):
    """-> V (n, 3), faces (lists, 0-based), group name of each face."""
    V, faces, groups = [], [], []
    cur = None
    with open(path) as fh:
        for line in fh:
            if line.startswith("v "):
                V.append([float(t) for t in line.split()[1:4]])
            elif line.startswith("g "):
                cur = line.split()[1] if len(line.split()) > 1 else None
            elif line.startswith("f "):
                faces.append([int(t.split("/")[0]) - 1 for t in line.split()[1:]])
                groups.append(cur)
    return np.array(V), faces, groups


def parse_off(text):
    toks = []
    for line in text.splitlines():
        line = line.split("#")[0].strip()
        if line:
            toks.extend(line.split())
    if toks[0] in ("OFF", "COFF", "NOFF"):
        toks = toks[1:]
    elif toks[0].endswith("OFF"):
        toks = toks[1:]
    nv, nf = int(toks[0]), int(toks[1])
    k = 3
    V = np.array(toks[k:k + 3 * nv], float).reshape(nv, 3)
    k += 3 * nv
    faces = []
    for _ in range(nf):
        n = int(toks[k])
        faces.append([int(t) for t in toks[k + 1:k + 1 + n]])
        k += 1 + n
        # colour values after the indices (COFF) are not used by these files
    return V, faces


def read_cgal_off(name):
    """data/meshes/NAME from CGAL's data archive (Debian libcgal-demo)."""
    if not os.path.exists(CGAL_DATA):
        raise SystemExit("make_swings.py: %s missing: scripts/deps.sh libcgal-demo" % CGAL_DATA)
    with tarfile.open(CGAL_DATA) as tf:
        text = tf.extractfile("data/meshes/%s" % name).read().decode()
    return parse_off(text)


def makehuman():
    V, faces, groups = read_obj_groups(os.path.join(DATA, "obj/makehuman/base.obj"))
    joints = {}
    for f, g in zip(faces, groups):
        if g and g.startswith("joint-"):
            joints.setdefault(g, set()).update(f)
    joints = {g: V[sorted(vs)].mean(0) for g, vs in joints.items()}
    body = [f for f, g in zip(faces, groups) if g == "body"]
    used = np.unique(np.concatenate([np.array(f) for f in body]))
    # keep only the body's vertices (renumbered in file order)
    remap = -np.ones(len(V), np.int64)
    remap[used] = np.arange(len(used))
    return V[used], [[int(remap[v]) for v in f] for f in body], joints


# ---------------------------------------------------------------- geometry

def rotation(axis, angle):
    a = np.asarray(axis, float)
    a = a / np.linalg.norm(a)
    K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


def edges_of(faces):
    e = []
    for f in faces:
        for k in range(len(f)):
            a, b = f[k], f[(k + 1) % len(f)]
            e.append((min(a, b), max(a, b)))
    return np.unique(np.array(e), axis=0)


def component_of(n, edges, mask, seed):
    """Vertices reachable from seed through edges whose both ends are in mask."""
    import scipy.sparse as sp
    import scipy.sparse.csgraph as cg
    keep = mask[edges[:, 0]] & mask[edges[:, 1]]
    e = edges[keep]
    A = sp.coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n, n))
    _, lab = cg.connected_components(A, directed=False)
    out = mask & (lab == lab[seed])
    return out


def smoothstep(x):
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3 - 2 * x)


class Joint:
    def __init__(self, j, d, axis, blend, radius, patch, seed, theta0, theta, phi):
        self.j = np.asarray(j, float)
        self.d = np.asarray(d, float) / np.linalg.norm(d)
        a = np.asarray(axis, float)
        a = a - a.dot(self.d) * self.d
        self.a = a / np.linalg.norm(a)
        self.blend, self.radius, self.patch = blend, radius, patch
        self.seed = seed
        self.theta0, self.theta, self.phi = map(math.radians, (theta0, theta, phi))


def weights(V, faces, jt):
    rel = V - jt.j
    along = rel @ jt.d
    radial = np.linalg.norm(rel - along[:, None] * jt.d, axis=1)
    limb = (along > -jt.blend) & (radial < jt.radius)
    seed = int(np.argmin(np.linalg.norm(V - jt.seed, axis=1)))
    if not limb[seed]:
        raise SystemExit("make_swings.py: the seed vertex is not in the limb")
    limb = component_of(len(V), edges_of(faces), limb, seed)
    w = np.where(limb, smoothstep((along + jt.blend) / (2 * jt.blend)), 0.0)
    return w, limb, along


def largest_component(faces, ids):
    """The largest edge-connected component of the faces `ids` (indices into `faces`), sorted."""
    parent = {i: i for i in ids}

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x
    emap = {}
    for i in ids:
        f = faces[i]
        for k in range(len(f)):
            e = (min(f[k], f[(k + 1) % len(f)]), max(f[k], f[(k + 1) % len(f)]))
            emap.setdefault(e, []).append(i)
    for fs in emap.values():
        for o in fs[1:]:
            ra, rb = find(fs[0]), find(o)
            if ra != rb:
                parent[ra] = rb
    comps = {}
    for i in ids:
        comps.setdefault(find(i), []).append(i)
    return sorted(max(comps.values(), key=len))


def band_patch(V, faces, jt, limb, along):
    """Faces whose every corner is within jt.patch of the joint along the bone and within
    jt.radius of its line, in the edge-connected component of such vertices that holds the
    limb vertex nearest the joint; then the largest edge-connected component of those faces."""
    rel = V - jt.j
    radial = np.linalg.norm(rel - along[:, None] * jt.d, axis=1)
    near = (np.abs(along) <= jt.patch) & (radial < jt.radius)
    start = int(np.argmin(np.where(limb & near, np.abs(along), np.inf)))
    near = component_of(len(V), edges_of(faces), near, start)
    ids = [i for i, f in enumerate(faces) if all(near[v] for v in f)]
    return largest_component(faces, ids)


def pose(V, w, jt, t, n):
    ph = 2 * math.pi * t / n
    p = (1 - math.cos(ph)) / 2
    theta = jt.theta0 + jt.theta * p
    phi = jt.phi * math.sin(ph)
    R = rotation(jt.a, theta) @ rotation(jt.d, phi)
    if getattr(jt, "skin", None) is not None:   # the model's own skin and weights
        return jt.skin.pose("Skeleton_arm_joint_L__3_", R)
    moved = jt.j + (V - jt.j) @ R.T
    return (1 - w)[:, None] * V + w[:, None] * moved


# ---------------------------------------------------------------- cases

def tube():
    na, nl = 24, 16
    V, faces = [], []
    for i in range(nl):
        s = i / (nl - 1)
        x = -3 + 6 * (s + 0.06 * math.sin(2 * math.pi * s))   # uneven spacing along
        r = 1 + 0.15 * math.sin(3 * s + 0.5)
        for k in range(na):
            a = 2 * math.pi * (k + 0.5 * (i % 2)) / na
            V.append([x, r * math.cos(a), r * 1.1 * math.sin(a)])
    for i in range(nl - 1):
        for k in range(na):
            a, b = i * na + k, i * na + (k + 1) % na
            faces.append([a, b, b + na, a + na])
    V = np.array(V)
    jt = Joint(j=[0, 0, 0], d=[1, 0, 0], axis=[0, 0, 1], blend=0.8, radius=5, patch=1.6,
               seed=[3, 0, 1], theta0=10, theta=70, phi=20)
    return V, faces, jt, "made here: a tube of 24 x 16 quads along x, radius 1 + 0.15 sin"


def mh_elbow():
    V, faces, J = makehuman()
    sh, el, ha = J["joint-l-shoulder"], J["joint-l-elbow"], J["joint-l-hand"]
    d = ha - el
    up = el - sh
    axis = np.cross(up, d)
    L = np.linalg.norm(d)
    jt = Joint(j=el, d=d, axis=axis, blend=0.2 * L, radius=0.45 * L, patch=0.45 * L,
               seed=ha + 0.3 * (ha - el), theta0=10, theta=70, phi=25)
    return V, faces, jt, ("MakeHuman base mesh (CC0 1.0), group body, left elbow "
                          "(helper cubes joint-l-elbow -> joint-l-hand)")


def mh_finger():
    V, faces, J = makehuman()
    a, b, c = J["joint-l-finger-3-1"], J["joint-l-finger-3-2"], J["joint-l-finger-3-3"]
    e = J["joint-l-finger-3-4"]
    d = c - b
    L = np.linalg.norm(d)
    axis = np.cross(b - a, d)
    if np.linalg.norm(axis) < 1e-3 * L * np.linalg.norm(b - a):
        axis = np.cross(d, [0, 1, 0])
    jt = Joint(j=b, d=d, axis=axis, blend=0.35 * L, radius=0.9 * L, patch=0.7 * L,
               seed=e + 0.5 * (e - c), theta0=10, theta=60, phi=15)
    return V, faces, jt, ("MakeHuman base mesh (CC0 1.0), group body, left middle finger at "
                          "joint-l-finger-3-2 (bone towards joint-l-finger-3-3)")


def cgal_hand():
    V, faces = read_cgal_off("hand.off")
    jt = Joint(j=[0, -0.05, -0.27], d=[0, 0, 1], axis=[1, 0, 0], blend=0.1, radius=2.0,
               patch=0.17, seed=[0, 0, 0.5], theta0=8, theta=45, phi=20)
    return V, faces, jt, ("CGAL data/meshes/hand.off (Debian libcgal-demo 5.5.1-2; CC0 1.0 "
                          "per the package's copyright file), wrist")


def cgal_camel():
    V, faces = read_cgal_off("camel.off")
    # front left leg: x > 0, z > 0 (head at +z), y up; knee about 40% down the leg
    legs = (V[:, 1] < -0.2) & (V[:, 0] > 0) & (V[:, 2] > 0)
    foot = V[legs][np.argmin(V[legs][:, 1])]
    top = V[legs][np.argmax(V[legs][:, 1])]
    knee = foot + 0.55 * (top - foot)
    idx = legs & (np.abs(V[:, 1] - knee[1]) < 0.02)
    knee = V[idx].mean(0)
    d = foot - knee
    L = np.linalg.norm(d)
    jt = Joint(j=knee, d=d, axis=[1, 0, 0], blend=0.12 * L, radius=0.25 * L, patch=0.3 * L,
               seed=foot, theta0=8, theta=55, phi=15)
    return V, faces, jt, ("CGAL data/meshes/camel.off (Debian libcgal-demo 5.5.1-2; CC0 1.0 "
                          "per the package's copyright file), front left knee")


def _local(node):
    if "matrix" in node:
        return np.array(node["matrix"], float).reshape(4, 4).T   # glTF: column-major
    M = np.eye(4)
    x, y, z, w = node.get("rotation", [0, 0, 0, 1])
    R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    M[:3, :3] = R * np.array(node.get("scale", [1, 1, 1]))[None, :]
    M[:3, 3] = node.get("translation", [0, 0, 0])
    return M


class GltfSkin:
    """Mesh 0 of a glTF file with its skin: positions welded as `quality.py gltf-bind` welds
    them (exact equality, numbered by first occurrence; a welded vertex keeps its first
    occurrence's joints and weights), posed by linear blend skinning from the nodes' own
    transforms, one joint's subtree turned about that joint."""

    def __init__(self, path):
        import quality
        doc, bufs = quality._load_gltf(path)
        self.doc = doc
        parent = {}
        for i, n in enumerate(doc["nodes"]):
            for c in n.get("children", []):
                parent[c] = i
        self.parent = parent
        G = {}

        def glob_(i):
            if i not in G:
                L = _local(doc["nodes"][i])
                G[i] = glob_(parent[i]) @ L if i in parent else L
            return G[i]
        for i in range(len(doc["nodes"])):
            glob_(i)
        self.G = G
        skin = doc["skins"][0]
        self.joints = skin["joints"]
        self.ibm = quality._accessor(doc, bufs, skin["inverseBindMatrices"]).reshape(
            -1, 4, 4).transpose(0, 2, 1).astype(float)
        index, verts, J, W, tris = {}, [], [], [], []
        for prim in doc["meshes"][0]["primitives"]:
            P = quality._accessor(doc, bufs, prim["attributes"]["POSITION"])
            Jp = quality._accessor(doc, bufs, prim["attributes"]["JOINTS_0"])
            Wp = quality._accessor(doc, bufs, prim["attributes"]["WEIGHTS_0"])
            ids = np.empty(len(P), np.int64)
            for i, p in enumerate(P):
                key = tuple(float(c) for c in p)
                k = index.get(key)
                if k is None:
                    k = index[key] = len(verts)
                    verts.append(key)
                    J.append(Jp[i].astype(np.int64))
                    W.append(Wp[i].astype(float))
                ids[i] = k
            I = quality._accessor(doc, bufs, prim["indices"]).reshape(-1).astype(np.int64) \
                if "indices" in prim else np.arange(len(P))
            tris.extend(ids[I].reshape(-1, 3).tolist())
        self.P = np.array(verts)
        self.J = np.array(J)
        self.W = np.array(W)
        self.W /= self.W.sum(1, keepdims=True)
        self.faces = tris

    def node(self, name):
        return next(i for i, n in enumerate(self.doc["nodes"]) if n.get("name") == name)

    def position(self, name):
        return self.G[self.node(name)][:3, 3].copy()

    def subtree(self, i):
        out = {i}
        for c in self.doc["nodes"][i].get("children", []):
            out |= self.subtree(c)
        return out

    def pose(self, joint=None, R=None):
        G = dict(self.G)
        if joint is not None:
            i = self.node(joint)
            p = G[i][:3, 3]
            M = np.eye(4)
            M[:3, :3] = R
            M[:3, 3] = p - R @ p
            for k in self.subtree(i):
                G[k] = M @ G[k]
        mats = np.stack([G[j] @ self.ibm[k] for k, j in enumerate(self.joints)])
        Ph = np.hstack([self.P, np.ones((len(self.P), 1))])
        out = np.zeros((len(self.P), 3))
        for c in range(self.J.shape[1]):
            out += self.W[:, c:c + 1] * np.einsum("nij,nj->ni", mats[self.J[:, c]], Ph)[:, :3]
        return out


def cesium_elbow():
    sk = GltfSkin(os.path.join(DATA, "gltf/CesiumMan.glb"))
    sh, el, wr = (sk.position(n) for n in ("Skeleton_arm_joint_L__4_", "Skeleton_arm_joint_L__3_",
                                          "Skeleton_arm_joint_L__2_"))
    d = wr - el
    L = np.linalg.norm(d)
    axis = np.cross(el - sh, d)
    if np.linalg.norm(axis) < 0.05 * L * np.linalg.norm(el - sh):
        axis = np.cross(d, [0, 0, 1])
    V = sk.pose()
    jt = Joint(j=el, d=d, axis=axis, blend=0.2 * L, radius=0.6 * L, patch=0.6 * L,
               seed=wr + 0.3 * d, theta0=10, theta=70, phi=25)
    jt.skin = sk
    return V, sk.faces, jt, ("CesiumMan.glb (CC-BY 4.0, Cesium) with its own skin and weights, "
                             "left elbow (node Skeleton_arm_joint_L__3_) turned")


CASES = {"swing-tube": tube, "swing-elbow": mh_elbow, "swing-finger": mh_finger,
         "swing-hand": cgal_hand, "swing-camel": cgal_camel, "swing-cesium": cesium_elbow}


# ---------------------------------------------------------------- output

def write_obj(path, V, faces, comment):
    with open(path, "w") as fh:
        fh.write("# %s\n" % comment)
        fh.write("".join("v %.6f %.6f %.6f\n" % tuple(p) for p in V))
        fh.write("".join("f " + " ".join(str(v + 1) for v in f) + "\n" for f in faces))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("case", nargs="?")
    ap.add_argument("out", nargs="?")
    ap.add_argument("--frames", type=int, default=60)
    ap.add_argument("--list", action="store_true")
    a = ap.parse_args(argv)
    if a.list:
        print(" ".join(CASES))
        return 0
    if a.case not in CASES or not a.out:
        ap.error("CASE (one of %s) and OUTDIR are required" % ", ".join(CASES))
    V, faces, jt, source = CASES[a.case]()
    w, limb, along = weights(V, faces, jt)
    patch = band_patch(V, faces, jt, limb, along)
    if not patch:
        raise SystemExit("make_swings.py: %s: empty patch" % a.case)
    os.makedirs(os.path.join(a.out, "frames"), exist_ok=True)
    write_obj(os.path.join(a.out, "bind.obj"), V, faces, "%s bind: %s" % (a.case, source))
    with open(os.path.join(a.out, "patch.txt"), "w") as fh:
        fh.write("# %s: faces within %.4g of the joint along the bone, in the limb\n"
                 % (a.case, jt.patch))
        for k in range(0, len(patch), 16):
            fh.write(" ".join(str(i) for i in patch[k:k + 16]) + "\n")
    for t in range(a.frames):
        write_obj(os.path.join(a.out, "frames", "swing.%04d.obj" % t), pose(V, w, jt, t, a.frames),
                  faces, "%s frame %d of %d" % (a.case, t, a.frames))
    pv = np.unique([v for i in patch for v in faces[i]])
    print("%s: %s; %d vertices, %d faces; %d limb vertices (weight > 0: %d); patch %d faces, "
          "%d vertices; %d frames, bend %.0f..%.0f deg, twist +-%.0f deg (period %d)"
          % (a.case, source, len(V), len(faces), int(limb.sum()), int((w > 0).sum()), len(patch),
             len(pv), a.frames, math.degrees(jt.theta0), math.degrees(jt.theta0 + jt.theta),
             math.degrees(jt.phi), a.frames))
    return 0


if __name__ == "__main__":
    sys.exit(main())
