#!/usr/bin/python3
"""The stress corpus of scripts/stress.sh: meshes of the kinds a pipeline meets, bent.

    make_stress.py CASE OUTDIR [--frames N]
    make_stress.py --list

Writes OUTDIR/bind.obj, OUTDIR/patch.txt (plain 0-based face ids) and OUTDIR/frames/
bend.0001.obj .. bend.000N.obj (default N = 3), and prints one line describing the case: source,
counts and what makes it hard (smallest and largest triangle angle of the patch, triangles with an
angle under 1 and 0.1 degree, caps with an angle over 170 degrees). Deterministic: the same
inputs give the same bytes (Blender's decimation included). Needs /usr/bin/python3 with numpy
and scipy; the decimated case also needs `blender` (Debian's 3.4: scripts/deps.sh blender).

Bends, as the synthetic bench's (tests/bench/bench_case.cpp: two-bone linear blend skinning,
20 to 80 degrees): frame k = 1..N at bend theta_k = AMP (20 + 60 |sin(pi k / 8)|) degrees about
the joint's bend axis, with a twist of 0.3 theta_k about the child bone;
x' = (1 - w) x + w (j + R (x - j)), w a smoothstep along the bone from BLEND before the joint to
BLEND after it, 0 outside the limb (the edge-connected piece, holding a seed point at the
limb's end, of the vertices beyond the blend's start and within RADIUS of the bone's line; see
scripts/make_swings.py, whose rig this is). AMP is 1, or 0.5 for the whole heads. Patches: a band
round the joint (faces within PATCH of it along the bone and within RADIUS of its line, the
largest edge-connected component; the faces round a bow-tie vertex dropped), or the whole mesh.

Sources. CGAL's data: Debian's libcgal-demo 5.5.1-2 ships CGAL 5.5.1's data folder as
/usr/share/doc/libcgal-dev/data.tar.gz (scripts/deps.sh libcgal-demo; override with CGAL_DATA);
its meshes carry no notice of their own, and the package's copyright file (CGAL's LICENSE) puts
every CGAL file without an explicit notice under CC0 1.0. Some are older public models (the
armadillo is the Stanford 3D Scanning Repository's, the camel is from Sumner & Popovic's
deformation-transfer meshes); tests/bench/stress.md lists each. MakeHuman's base mesh (CC0 1.0)
from QUALITY_DATA (default /work/shared/data). Nothing is copied into the repository: every
case is made here at run time from those files.

Cases:
  devil-head     CGAL mannequin-devil.off: a sculpted head with horns and fangs (12977
                 vertices, slivers down to 0.03 degrees, 51 caps), the whole head one patch
                 (its one loop is the neck opening); nodding bend at the head's centre, AMP 0.5.
  devil-band     the same head and bend; a band across it (within 0.15 of the height).
  lion-head      CGAL lion-head.off: a sculpt with fine detail (8356 vertices, open at the
                 neck), the whole head one patch; bend at its centre, AMP 0.5.
  head-whole     CGAL head.off: a coarse scanned-style head (1487 vertices, neck and two eye
                 holes), the whole head one patch: a strongly curved chart; AMP 0.5.
  man-torso      CGAL man.off: a scanned body (17495 vertices, slivers down to 0.025 degrees,
                 40 caps), the upper body from waist to chin one patch (arms cut at the
                 wrists), bent forward at the waist.
  dragon-body    CGAL ChineseDragon-10kv.off: a decimated statue scan (10000 vertices,
                 slivers 0.07 degrees, 103 caps), a band round the body (0.2 of the height
                 either side of its middle), bent there.
  triceratops    CGAL triceratops.off: horns and slivers down to 0.0002 degrees (2832
                 vertices), band round the neck, the head nodding.
  bull-neck      CGAL bull.off: horns, 11 caps (6200 vertices), band round the neck.
  armadillo-dec  CGAL armadillo.off (the Stanford scan, 26002 vertices) decimated by
                 Blender's Decimate modifier (collapse, ratio 0.1) to about 2600 vertices:
                 a decimated mesh's slivers and needles; band round the waist.
  knee-needles   MakeHuman's body (CC0), left knee band; every quad of the mesh split into 4
                 triangles about a point 98% of the way from its centre to one edge's
                 midpoint: a cap (about 176 degrees) and two needles per quad.
  elbow-slivers  MakeHuman's body, left elbow band; quads split in two, then every 5th vertex
                 of the band's interior moved 99.9% of the way to a neighbour: slivers under
                 0.1 degree round each.
  cow-cut        CGAL cow.off (2904 vertices, closed, genus 0), a small hole cut in its back
                 (faces with a corner within 0.04 of its length of the top of the back); the
                 whole rest of the animal one patch: a strongly curved chart (a nearly closed
                 surface with legs, horns and tail on a disk); the head and neck bent.
                 (CGAL's elephant.off, first tried, is closed with genus 3, Euler
                 characteristic -4: no small cut makes it a disk.)
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_swings import (Joint, band_patch, largest_component, makehuman, parse_off,  # noqa: E402
                         read_cgal_off, rotation, weights, write_obj)

BLENDER = os.environ.get("BLENDER", "blender")

DECIMATE_PY = r'''
import sys, bpy, numpy as np
src, dst, ratio = sys.argv[sys.argv.index("--") + 1:]
V, F = [], []
for line in open(src):
    p = line.split()
    if p and p[0] == "v": V.append([float(x) for x in p[1:4]])
    elif p and p[0] == "f": F.append([int(x) - 1 for x in p[1:]])
me = bpy.data.meshes.new("m")
me.from_pydata(V, [], F)
me.update()
ob = bpy.data.objects.new("m", me)
bpy.context.scene.collection.objects.link(ob)
bpy.context.view_layer.objects.active = ob
md = ob.modifiers.new("d", "DECIMATE")
md.decimate_type = "COLLAPSE"
md.ratio = float(ratio)
md.use_collapse_triangulate = True
dg = bpy.context.evaluated_depsgraph_get()
m2 = ob.evaluated_get(dg).to_mesh()
with open(dst, "w") as fh:
    fh.write("OFF\n%d %d 0\n" % (len(m2.vertices), len(m2.polygons)))
    for v in m2.vertices: fh.write("%.9g %.9g %.9g\n" % tuple(v.co))
    for p in m2.polygons: fh.write("%d %s\n" % (len(p.vertices), " ".join(map(str, p.vertices))))
'''


# ---------------------------------------------------------------- degradations

def decimate(V, faces, ratio):
    with tempfile.TemporaryDirectory() as tmp:
        src, dst, py = (os.path.join(tmp, n) for n in ("in.obj", "out.off", "dec.py"))
        write_obj(src, V, faces, "decimate input")
        with open(py, "w") as fh:
            fh.write(DECIMATE_PY)
        r = subprocess.run([BLENDER, "-b", "--factory-startup", "-noaudio", "--python-exit-code",
                            "1", "--python", py, "--", src, dst, str(ratio)],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if r.returncode != 0 or not os.path.exists(dst):
            sys.stderr.write(r.stdout[-2000:])
            raise SystemExit("make_stress.py: Blender's decimation failed (%s)" % BLENDER)
        V2, F2 = parse_off(open(dst).read())
    used = np.unique(np.concatenate([np.array(f) for f in F2]))
    remap = -np.ones(len(V2), np.int64)
    remap[used] = np.arange(len(used))
    return V2[used], [[int(remap[v]) for v in f] for f in F2]


def quads_to_needles(V, faces):
    """Every quad -> 4 triangles about a point 98% of the way from its centre to the midpoint
    of its first edge (a cap at that point, needles beside it); triangles kept."""
    V = [tuple(p) for p in V]
    out = []
    for f in faces:
        if len(f) != 4:
            out.append(f)
            continue
        P = np.array([V[v] for v in f])
        c = P.mean(0)
        m = 0.5 * (P[0] + P[1])
        q = c + 0.98 * (m - c)
        V.append(tuple(q))
        k = len(V) - 1
        out += [[f[0], f[1], k], [f[1], f[2], k], [f[2], f[3], k], [f[3], f[0], k]]
    return np.array(V), out


def split_quads(faces):
    out = []
    for f in faces:
        for k in range(1, len(f) - 1):
            out.append([f[0], f[k], f[k + 1]])
    return out


def collapse_slivers(V, faces, patch_ids, step=5, share=0.999):
    """Every `step`-th interior vertex of the patch moves `share` of the way to its
    lowest-numbered neighbour: its triangles round that edge become slivers."""
    V = V.copy()
    cnt = {}
    for i in patch_ids:
        f = faces[i]
        for k in range(3):
            e = (min(f[k], f[(k + 1) % 3]), max(f[k], f[(k + 1) % 3]))
            cnt[e] = cnt.get(e, 0) + 1
    border = {v for e, c in cnt.items() if c == 1 for v in e}
    nbr = {}
    for (a, b) in cnt:
        nbr.setdefault(a, set()).add(b)
        nbr.setdefault(b, set()).add(a)
    inner = sorted(v for v in nbr if v not in border)
    moved = set()
    for v in inner[::step]:
        cands = sorted(u for u in nbr[v] if u not in moved)
        if not cands:
            continue
        u = cands[0]
        V[v] = V[v] + share * (V[u] - V[v])
        moved.add(v)
    return V, len(moved)


# ---------------------------------------------------------------- helpers

def extent(V):
    lo, hi = V.min(0), V.max(0)
    return lo, hi, hi - lo


def all_faces(faces):
    return list(range(len(faces)))


def cut_hole(V, faces, centre, radius):
    """Drops the faces with a corner within radius of centre; the rest, largest piece."""
    near = np.linalg.norm(V - centre, axis=1) < radius
    keep = [f for f in faces if not any(near[v] for v in f)]
    used = np.unique(np.concatenate([np.array(f) for f in keep]))
    remap = -np.ones(len(V), np.int64)
    remap[used] = np.arange(len(used))
    return V[used], [[int(remap[v]) for v in f] for f in keep]


# ---------------------------------------------------------------- cases
# Each returns V, faces, joint, patch ids, amplitude, source text.

def whole_head(name, up, bend_axis, src):
    V, faces = read_cgal_off(name)
    lo, hi, ext = extent(V)
    c = 0.5 * (lo + hi)
    u = np.eye(3)[up]
    h = ext[up]
    jt = Joint(j=c, d=u, axis=np.eye(3)[bend_axis], blend=0.3 * h, radius=10 * h, patch=h,
               seed=c + 0.6 * h * u, theta0=0, theta=0, phi=0)
    return V, faces, jt, all_faces(faces), 0.5, src


def devil_head():
    return whole_head("mannequin-devil.off", 2, 0, "CGAL mannequin-devil.off, whole head")


def devil_band():
    V, faces, jt, _, amp, _ = devil_head()
    jt.patch = 0.15 * extent(V)[2][2]
    return V, faces, jt, None, amp, "CGAL mannequin-devil.off, band across the head"


def lion_head():
    return whole_head("lion-head.off", 2, 0, "CGAL lion-head.off, whole head")


def head_whole():
    return whole_head("head.off", 1, 0, "CGAL head.off, whole head (neck and eye holes)")


def man_torso():
    V, faces = read_cgal_off("man.off")          # z up, height 1
    lo, hi, ext = extent(V)
    c = 0.5 * (lo + hi)
    h = ext[2]
    j = np.array([c[0], c[1], lo[2] + 0.58 * h])
    jt = Joint(j=j, d=[0, 0, 1], axis=[1, 0, 0], blend=0.1 * h, radius=10 * h, patch=h,
               seed=[c[0], c[1], hi[2]], theta0=0, theta=0, phi=0)
    # the patch: faces with every corner between 0.46 and 0.96 of the height (waist to
    # chin: the armpits' and the face's slivers), the largest component
    z = (V[:, 2] - lo[2]) / h
    ids = [i for i, f in enumerate(faces) if all(0.46 <= z[v] <= 0.96 for v in f)]
    return V, faces, jt, no_bowties(faces, largest_component(faces, ids)), 1.0, \
        "CGAL man.off, upper body"


def no_bowties(faces, ids):
    """Drops the faces round every vertex whose patch faces form more than one fan (a
    bow-tie, which a patch may not have), then keeps the largest component; repeated."""
    while True:
        fan_of = {}
        for i in ids:
            for v in faces[i]:
                fan_of.setdefault(v, []).append(i)
        bad = set()
        for v, fs in fan_of.items():
            # faces round v joined through the edges at v
            parent = {i: i for i in fs}

            def find(x):
                while parent[x] != x:
                    x = parent[x]
                return x
            by_edge = {}
            for i in fs:
                f = faces[i]
                k = f.index(v)
                for u in (f[k - 1], f[(k + 1) % len(f)]):
                    by_edge.setdefault(u, []).append(i)
            for group in by_edge.values():
                for o in group[1:]:
                    parent[find(group[0])] = find(o)
            if len({find(i) for i in fs}) > 1:
                bad.update(fs)
        if not bad:
            return ids
        ids = largest_component(faces, [i for i in ids if i not in bad])


def dragon_body():
    V, faces = read_cgal_off("ChineseDragon-10kv.off")
    lo, hi, ext = extent(V)
    c = 0.5 * (lo + hi)
    h = ext[1]
    jt = Joint(j=c, d=[0, 1, 0], axis=[1, 0, 0], blend=0.2 * h, radius=10 * h, patch=0.2 * h,
               seed=[c[0], hi[1], c[2]], theta0=0, theta=0, phi=0)
    return V, faces, jt, None, 1.0, "CGAL ChineseDragon-10kv.off, band round the body"


def triceratops():
    V, faces = read_cgal_off("triceratops.off")  # y up, head at +x
    lo, hi, ext = extent(V)
    j = np.array([3.3, 0.5 * (lo[1] + hi[1]) + 0.6, 0.0])
    jt = Joint(j=j, d=[1, 0, 0], axis=[0, 0, 1], blend=0.8, radius=4.5, patch=1.2,
               seed=[hi[0], j[1], 0], theta0=0, theta=0, phi=0)
    return V, faces, jt, None, 1.0, "CGAL triceratops.off, neck band"


def bull_neck():
    V, faces = read_cgal_off("bull.off")         # y up, head at -x
    lo, hi, ext = extent(V)
    sel = (np.abs(V[:, 0] + 0.28) < 0.02) & (V[:, 1] > 0)
    j = V[sel].mean(0)
    head = V[np.argmin(V[:, 0])]
    jt = Joint(j=j, d=[-1, 0, 0], axis=[0, 0, 1], blend=0.08, radius=0.25, patch=0.1,
               seed=head, theta0=0, theta=0, phi=0)
    return V, faces, jt, None, 1.0, "CGAL bull.off, neck band"


def armadillo_dec():
    V, faces = read_cgal_off("armadillo.off")    # y up
    V, faces = decimate(V, faces, 0.1)
    lo, hi, ext = extent(V)
    c = 0.5 * (lo + hi)
    h = ext[1]
    j = np.array([c[0], lo[1] + 0.45 * h, c[2]])
    jt = Joint(j=j, d=[0, 1, 0], axis=[1, 0, 0], blend=0.12 * h, radius=0.3 * h, patch=0.15 * h,
               seed=[c[0], hi[1] - 0.05 * h, c[2]], theta0=0, theta=0, phi=0)
    return V, faces, jt, None, 1.0, ("CGAL armadillo.off decimated by Blender (collapse, ratio "
                                      "0.1), waist band")


def mh_limb(a, b, tip):
    V, faces, J = makehuman()
    j, e = J[a], J[b]
    d = e - j
    L = np.linalg.norm(d)
    axis = np.cross(d, [0, 0, 1]) if abs(d[2]) < 0.9 * L else np.cross(d, [1, 0, 0])
    jt = Joint(j=j, d=d, axis=axis, blend=0.2 * L, radius=0.45 * L, patch=0.35 * L,
               seed=J[tip] + 0.1 * d, theta0=0, theta=0, phi=0)
    return V, faces, jt


def knee_needles():
    V, faces, jt = mh_limb("joint-l-knee", "joint-l-ankle", "joint-l-ankle")
    V, faces = quads_to_needles(V, faces)
    return V, faces, jt, None, 1.0, "MakeHuman body, left knee band, quads split into needles"


def elbow_slivers():
    V, faces, jt = mh_limb("joint-l-elbow", "joint-l-hand", "joint-l-hand-3")
    faces = split_quads(faces)
    return V, faces, jt, None, 1.0, "MakeHuman body, left elbow band, collapsed into slivers"


def cow_cut():
    V, faces = read_cgal_off("cow.off")          # x: length (head at -x), y up; genus 0
    lo, hi, ext = extent(V)
    top = V[np.argmax(V[:, 1] - 2.0 * np.abs(V[:, 0] - 0.5 * (lo[0] + hi[0])))]
    V, faces = cut_hole(V, faces, top, 0.04 * ext[0])
    lo, hi, ext = extent(V)
    c = 0.5 * (lo + hi)
    j = np.array([lo[0] + 0.3 * ext[0], c[1], c[2]])
    jt = Joint(j=j, d=[-1, 0, 0], axis=[0, 0, 1], blend=0.1 * ext[0], radius=10 * ext[0],
               patch=10 * ext[0], seed=[lo[0], c[1], c[2]], theta0=0, theta=0, phi=0)
    return V, faces, jt, all_faces(faces), 1.0, ("CGAL cow.off, a small hole cut in its back, "
                                                  "the whole rest one patch")


CASES = {"devil-head": devil_head, "devil-band": devil_band, "lion-head": lion_head,
         "head-whole": head_whole, "man-torso": man_torso, "dragon-body": dragon_body,
         "triceratops": triceratops, "bull-neck": bull_neck, "armadillo-dec": armadillo_dec,
         "knee-needles": knee_needles, "elbow-slivers": elbow_slivers,
         "cow-cut": cow_cut}


# ---------------------------------------------------------------- figures

def angle_stats(V, faces, ids):
    T = np.array([t for i in ids for t in split_quads([faces[i]])])
    P = V[T]
    ang = []
    for k in range(3):
        a = P[:, (k + 1) % 3] - P[:, k]
        b = P[:, (k + 2) % 3] - P[:, k]
        cosang = np.einsum("ij,ij->i", a, b) / np.maximum(
            np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1), 1e-300)
        ang.append(np.degrees(np.arccos(np.clip(cosang, -1, 1))))
    A = np.stack(ang, 1)
    return {"triangles": len(T), "min_angle": float(A.min()), "max_angle": float(A.max()),
            "under_1": int((A.min(1) < 1).sum()), "under_0.1": int((A.min(1) < 0.1).sum()),
            "caps_over_170": int((A.max(1) > 170).sum())}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("case", nargs="?")
    ap.add_argument("out", nargs="?")
    ap.add_argument("--frames", type=int, default=3)
    ap.add_argument("--list", action="store_true")
    a = ap.parse_args(argv)
    if a.list:
        print(" ".join(CASES))
        return 0
    if a.case not in CASES or not a.out:
        ap.error("CASE (one of %s) and OUTDIR are required" % ", ".join(CASES))
    V, faces, jt, patch, amp, source = CASES[a.case]()
    w, limb, along = weights(V, faces, jt)
    extra = ""
    if patch is None:
        patch = no_bowties(faces, band_patch(V, faces, jt, limb, along))
    if a.case == "elbow-slivers":
        V, moved = collapse_slivers(V, faces, patch)
        w, limb, along = weights(V, faces, jt)
        extra = "; %d vertices collapsed" % moved
    os.makedirs(os.path.join(a.out, "frames"), exist_ok=True)
    write_obj(os.path.join(a.out, "bind.obj"), V, faces, "%s bind: %s" % (a.case, source))
    with open(os.path.join(a.out, "patch.txt"), "w") as fh:
        fh.write("# %s\n" % a.case)
        for k in range(0, len(patch), 16):
            fh.write(" ".join(str(i) for i in patch[k:k + 16]) + "\n")
    for k in range(1, a.frames + 1):
        theta = math.radians(amp * (20 + 60 * abs(math.sin(math.pi * k / 8))))
        R = rotation(jt.a, theta) @ rotation(jt.d, 0.3 * theta)
        P = (1 - w)[:, None] * V + w[:, None] * (jt.j + (V - jt.j) @ R.T)
        write_obj(os.path.join(a.out, "frames", "bend.%04d.obj" % k), P, faces,
                  "%s frame %d: bend %.1f deg" % (a.case, k, math.degrees(theta)))
    st = angle_stats(V, faces, patch)
    pv = np.unique([v for i in patch for v in faces[i]])
    print("%s: %s%s; mesh %d vertices, %d faces; patch %d faces (%d triangles), %d vertices; "
          "angles %.3g..%.4g deg, %d under 1 deg, %d under 0.1 deg, %d caps over 170 deg; "
          "%d frames, bend up to %.0f deg"
          % (a.case, source, extra, len(V), len(faces), len(patch), st["triangles"], len(pv),
             st["min_angle"], st["max_angle"], st["under_1"], st["under_0.1"],
             st["caps_over_170"], a.frames,
             amp * (20 + 60 * abs(math.sin(math.pi * a.frames / 8)))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
