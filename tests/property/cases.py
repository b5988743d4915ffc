"""Seeded generators of what users hand skinslide: meshes (data/, ../shared/data, small
degenerate ones made here), patch selections (grown, punched, stray faces, whole components,
several files; shared faces and bow-ties that must be refused), controls (pins, weights,
strength), options (both methods, report, dumps, previews, threads, limits), and frames (the
meshes' own, smooth deformations, collapses, the bind itself, broken files).

A case is a plain object built from one integer seed: the same seed gives the same case."""
import math
import pathlib

import numpy as np

from geometry import diagonal
from meshio import Glb, Obj, weld, write_obj
from topology import MeshTopology


# ---- meshes -------------------------------------------------------------------------------------

class Mesh:
    """A bind mesh the cases draw from. Positions and faces use skinslide's vertex ids (OBJ `v`
    order; glTF: welded)."""

    def __init__(self, name, path, kind, *, frames=(), clips=0, degenerate=False, heavy=False,
                 colours=False, closed=False):
        self.name, self.path, self.kind = name, str(path), kind
        self.own_frames = [str(f) for f in frames]   # files of the same topology
        self.clips = clips                            # glTF animations
        self.degenerate = degenerate                  # slivers, zero areas: paper may refuse
        self.heavy = heavy                            # large: smaller selections, fewer frames
        self.colours = colours                        # OBJ v lines carry r g b
        self._loaded = False

    def load(self):
        if self._loaded:
            return self
        if self.kind == "obj":
            self.obj = Obj.read(self.path)
            self.positions = self.obj.positions
            self.faces = self.obj.faces
            self.glb = None
        else:
            self.glb = Glb.read(self.path)
            self.positions, self.raw_ids = weld(self.glb.raw)
            self.faces = [list(map(int, self.raw_ids[t])) for t in self.glb.raw_triangles]
            self.obj = None
        self.topo = MeshTopology(self.faces)
        self.diag = diagonal(self.positions)
        self._loaded = True
        return self


def _grid(n, m, jitter, rng, sliver_columns=(), zero_rows=(), triangles=False):
    xs = np.linspace(0, 1, n + 1)
    for c in sliver_columns:  # squeeze a column of cells to 1e-7 of its width
        xs[c + 1:] -= (xs[c + 1] - xs[c]) * (1 - 1e-7)
    ys = np.linspace(0, 1, m + 1)
    for r in zero_rows:  # a row of cells with zero height: zero-area faces, zero-length edges
        ys[r + 1:] -= ys[r + 1] - ys[r]
    pos = []
    for j in range(m + 1):
        for i in range(n + 1):
            pos.append([xs[i], ys[j], 0.05 * math.sin(3 * xs[i]) * math.cos(2 * ys[j])])
    pos = np.array(pos) + jitter * rng.standard_normal((len(pos), 3)) / max(n, m)
    faces = []
    for j in range(m):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 2, a + n + 1
            if triangles:
                faces += [[a, b, c], [a, c, d]] if (i + j) % 2 else [[a, b, d], [b, c, d]]
            else:
                faces.append([a, b, c, d])
    return pos, faces


def make_synthetic(folder):
    """Small hand-made meshes of the kinds that break solvers: slivers, zero-area faces,
    duplicate positions, needles, polygons, a tube, closed and non-orientable surfaces, a
    non-manifold vertex, unused vertices, vertex colours. Written once per run."""
    folder = pathlib.Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(1234)
    out = []

    def add(name, pos, faces, colours=None, **kw):
        path = folder / f"{name}.obj"
        write_obj(path, pos, faces, colours)
        out.append(Mesh(name, path, "obj", colours=colours is not None, **kw))

    pos, faces = _grid(12, 10, 0.15, rng, triangles=True)
    add("grid_tri", pos, faces)
    pos, faces = _grid(9, 9, 0.0, rng)
    add("grid_quad_colours", pos, faces, colours=rng.random((len(pos), 3)))
    pos, faces = _grid(14, 8, 0.0, rng, sliver_columns=(3, 9), triangles=True)
    add("slivers", pos, faces, degenerate=True)
    pos, faces = _grid(10, 10, 0.0, rng, zero_rows=(4,))
    add("zero_area_rows", pos, faces, degenerate=True)
    # duplicate positions: a slit in a grid, its two lips distinct vertices at one position
    pos, faces = _grid(8, 8, 0.05, rng, triangles=True)
    remap = {}
    extra = []
    for j in (3, 4, 5):
        v = j * 9 + 4
        remap[v] = len(pos) + len(extra)
        extra.append(pos[v])
    pos = np.vstack([pos, extra])
    for f in faces:
        if all(v % 9 >= 4 for v in f) and any(v % 9 > 4 for v in f):
            f[:] = [remap.get(v, v) for v in f]
    add("slit_duplicates", pos, faces, degenerate=True)
    # needles and caps: a fan around a centre pushed almost onto one rim vertex
    k = 24
    rim = [[math.cos(2 * math.pi * i / k), math.sin(2 * math.pi * i / k), 0.1 * (i % 3)]
           for i in range(k)]
    mid = [[0.5 * math.cos(2 * math.pi * (i + 0.5) / k), 0.5 * math.sin(2 * math.pi * (i + 0.5) / k), 0]
           for i in range(k)]
    centre = [[0.999999 * mid[0][0], 0.999999 * mid[0][1], 0.0]]
    pos = np.array(rim + mid + centre)
    faces = []
    for i in range(k):
        a, b = i, (i + 1) % k
        ma, mb = k + i, k + (i + 1) % k
        faces += [[a, b, ma], [b, mb, ma], [ma, mb, 2 * k]]
    add("needles", pos, faces, degenerate=True)
    # polygons: pentagons and non-planar hexagons in a strip
    pos, faces = [], []
    for i in range(7):
        for j, y in enumerate((0, 1, 2)):
            pos.append([i, y, 0.3 * ((i + j) % 2)])
    for i in range(6):
        a = i * 3
        faces.append([a, a + 3, a + 4, a + 5, a + 2, a + 1])
    pos2 = np.array(pos, dtype=float)
    add("polygons", pos2, faces)
    # tube, open at both ends
    ring, rows = 16, 12
    pos = [[math.cos(2 * math.pi * i / ring), math.sin(2 * math.pi * i / ring), 0.4 * j]
           for j in range(rows + 1) for i in range(ring)]
    faces = []
    for j in range(rows):
        for i in range(ring):
            a, b = j * ring + i, j * ring + (i + 1) % ring
            faces.append([a, b, b + ring, a + ring])
    add("tube", np.array(pos), faces)
    # closed: an octahedron subdivided once
    verts = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]]
    tris = [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]
    verts, tris = _subdivide(verts, tris)
    add("ball", np.array(verts), tris)
    # Moebius strip
    n = 20
    pos, faces = [], []
    for i in range(n):
        t = 2 * math.pi * i / n
        for s in (-0.3, 0.3):
            pos.append([(1 + s * math.cos(t / 2)) * math.cos(t), (1 + s * math.cos(t / 2)) * math.sin(t),
                        s * math.sin(t / 2)])
    for i in range(n):
        a, b = 2 * i, 2 * ((i + 1) % n)
        if i == n - 1:
            faces.append([a, a + 1, b, b + 1])
        else:
            faces.append([a, a + 1, b + 1, b])
    add("moebius", np.array(pos), faces)
    # two sheets sharing one vertex (a non-manifold mesh), plus two unused vertices
    pa, fa = _grid(4, 4, 0.0, rng)
    pb = pa - pa[0] + pa[24]
    pb[:, 2] += 0.5 * (pb[:, 0] - pb[0, 0])
    pos = np.vstack([pa, pb[1:], [[9, 9, 9], [9, 9, 9.5]]])
    fb = [[24 if v == 0 else 24 + v for v in f] for f in fa]
    add("pinched_unused", pos, fa + fb, degenerate=True)
    # far from the origin and tiny / huge: tolerances are relative to the mesh
    pos, faces = _grid(10, 7, 0.1, rng, triangles=True)
    add("grid_far_tiny", pos * 1e-4 + np.array([3e2, -1e2, 5e1]), faces)
    ring, rows = 12, 8
    pos = [[math.cos(2 * math.pi * i / ring), math.sin(2 * math.pi * i / ring), 0.5 * j]
           for j in range(rows + 1) for i in range(ring)]
    faces = [[j * ring + i, j * ring + (i + 1) % ring, (j + 1) * ring + (i + 1) % ring,
              (j + 1) * ring + i] for j in range(rows) for i in range(ring)]
    add("tube_huge", np.array(pos) * 1e5 + 1e6, faces)
    # three sheets sharing one edge (a fin: an edge in three faces)
    pos, faces = _grid(6, 6, 0.05, rng, triangles=True)
    n0 = len(pos)
    col = [j * 7 + 3 for j in range(7)]  # the middle column, shared by the fin
    fin_pos, fin_faces, ids = [], [], {}
    for j in range(7):
        for i in range(1, 4):
            ids[(i, j)] = n0 + len(fin_pos)
            fin_pos.append([pos[col[j]][0], pos[col[j]][1], 0.3 * i])
    for j in range(6):
        for i in range(3):
            a = col[j] if i == 0 else ids[(i, j)]
            b = col[j + 1] if i == 0 else ids[(i, j + 1)]
            fin_faces.append([a, b, ids[(i + 1, j + 1)], ids[(i + 1, j)]])
    add("fin", np.vstack([pos, fin_pos]), faces + fin_faces, degenerate=True)
    # an OBJ with CRLF line ends, v lines with w, vt and vn lines, relative (negative) face
    # indices, groups, comments, v lines after f lines
    pos, faces = _grid(7, 6, 0.1, rng)
    lines = ["# quirks\r", "mtllib none.mtl\r", "o quirks\r", "g first\r"]
    half = len(pos) // 2
    for v in range(half):
        lines.append("v  %r %r %r 1.0\r" % tuple(map(float, pos[v])))
        lines.append("vt 0.5 0.5\r")
    lines.append("vn 0 0 1\r")
    done = []
    for f in faces:
        if max(f) < half:
            lines.append("f " + " ".join(f"{v - half}/1/1" for v in f) + "\r")
            done.append(f)
    lines.append("g second\r")
    for v in range(half, len(pos)):
        lines.append("v %r %r %r\r" % tuple(map(float, pos[v])))
    for f in faces:
        if f not in done:
            lines.append("f " + " ".join(f"{v + 1}//1" for v in f) + "\r")
    path = folder / "quirks.obj"
    path.write_bytes(("\n".join(lines) + "\n").encode())
    out.append(Mesh("quirks", path, "obj"))
    # a bind flat on a line: every vertex on the x axis
    pos, faces = _grid(6, 3, 0.0, rng, triangles=True)
    flat = np.zeros_like(pos)
    flat[:, 0] = pos[:, 0] + 0.37 * pos[:, 1]
    add("flat_line", flat, faces, degenerate=True)
    return out


def _subdivide(verts, tris):
    verts = [list(map(float, v)) for v in verts]
    mids = {}

    def mid(a, b):
        key = (min(a, b), max(a, b))
        if key not in mids:
            p = np.add(verts[a], verts[b]) / 2
            p = p / np.linalg.norm(p)
            mids[key] = len(verts)
            verts.append(list(p))
        return mids[key]

    out = []
    for a, b, c in tris:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        out += [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
    return verts, out


def catalogue(root, shared, work):
    """Every mesh the cases draw from: data/, ../shared/data (when present) and the synthetic
    ones (written into work/meshes)."""
    root, shared = pathlib.Path(root), pathlib.Path(shared)
    meshes = []
    for name in ("elbow", "face"):
        d = root / "data" / name
        meshes.append(Mesh(name, d / "bind.obj", "obj", frames=sorted((d / "frames").glob("*.obj"))))
    ict = shared / "data/obj/ict-facekit"
    if (ict / "generic_neutral_mesh.obj").exists():
        frames = [ict / f"{n}.obj" for n in ("jawOpen", "mouthSmile_L", "eyeBlink_L", "browInnerUp_L")]
        meshes.append(Mesh("ict_face", ict / "generic_neutral_mesh.obj", "obj",
                           frames=[f for f in frames if f.exists()], heavy=True))
    mh = shared / "data/obj/makehuman/base.obj"
    if mh.exists():
        meshes.append(Mesh("makehuman", mh, "obj", heavy=True))
    for name in ("CesiumMan", "Fox", "RiggedFigure", "RiggedSimple"):
        p = shared / "data/gltf" / f"{name}.glb"
        if p.exists():
            meshes.append(Mesh(name, p, "glb", clips=3 if name == "Fox" else 1))
    meshes += make_synthetic(pathlib.Path(work) / "meshes")
    return meshes


# ---- selections ---------------------------------------------------------------------------------

def _region(rng, mesh, kind, cap):
    topo, nf = mesh.topo, len(mesh.faces)
    seed = rng.randrange(nf)
    size = max(1, int(math.exp(rng.uniform(0, math.log(max(cap, 2))))))
    if kind == "single":
        return {seed}, "a single face"
    if kind == "strays":
        return {rng.randrange(nf) for _ in range(rng.randint(1, 5))}, "stray faces"
    if kind == "confetti":
        # many small patches at once: single faces and pairs scattered over the mesh
        out = set()
        for _ in range(rng.randint(20, 200)):
            f = rng.randrange(nf)
            out.add(f)
            if rng.random() < 0.3 and topo.neighbours[f]:
                out.add(rng.choice(topo.neighbours[f]))
        return out, "confetti of single faces and pairs"
    if kind == "grown":
        return topo.grow(rng, seed, size), f"a region grown to {size} faces"
    if kind == "punched":
        region = topo.grow(rng, seed, max(size, 12))
        inner = [f for f in region if all(g in region for g in topo.neighbours[f])]
        if not inner:
            return region, "a grown region (no inner face to punch)"
        holes = rng.randint(1, 3)
        for _ in range(holes):
            h = topo.grow(rng, rng.choice(inner), rng.randint(1, max(1, len(region) // 6)), region)
            region -= h
        return region, f"a region of {size} faces with {holes} holes punched"
    if kind == "subset":
        region = topo.grow(rng, seed, max(size, 4))
        keep = rng.uniform(0.3, 0.95)
        return {f for f in region if rng.random() < keep}, f"a random {keep:.2f} of a region"
    if kind == "component":
        comp = rng.choice(topo.components)
        if len(comp) > 4 * cap:
            return topo.grow(rng, comp[0], cap), "a region (component too large)"
        return set(comp), "a whole component"
    if kind == "whole":
        if nf > 4 * cap:
            return topo.grow(rng, seed, cap), "a region (mesh too large to take whole)"
        return set(range(nf)), "the whole mesh"
    if kind == "bowtie":
        # the 2-ring of a vertex, less two faces of its fan that share no edge: the vertex then
        # has two separate fans within one component
        for _ in range(20):
            v = rng.randrange(len(mesh.positions))
            fan = mesh.topo.vertex_faces.get(v, [])
            if len(fan) < 4:
                continue
            ring = set()
            for f in fan:
                for u in mesh.faces[f]:
                    ring.update(mesh.topo.vertex_faces[u])
            pairs = [(a, b) for a in fan for b in fan if a < b and b not in topo.neighbours[a]]
            if not pairs:
                continue
            a, b = rng.choice(pairs)
            return ring - {a, b}, f"a bow-tie at vertex {v}"
        return {seed}, "a single face (no bow-tie found)"
    if kind == "touching":
        # two faces meeting at one vertex only: two patches sharing a border vertex
        for _ in range(20):
            v = rng.randrange(len(mesh.positions))
            fan = mesh.topo.vertex_faces.get(v, [])
            pairs = [(a, b) for a in fan for b in fan if a < b and b not in topo.neighbours[a]]
            if pairs:
                return set(rng.choice(pairs)), f"two faces meeting at vertex {v} only"
        return {seed}, "a single face"
    raise ValueError(kind)


REGION_KINDS = [("grown", 36), ("punched", 14), ("single", 8), ("strays", 8), ("subset", 5),
                ("component", 5), ("whole", 4), ("bowtie", 2), ("touching", 4), ("confetti", 3)]


def _pick(rng, weighted):
    total = sum(w for _, w in weighted)
    x = rng.uniform(0, total)
    for item, w in weighted:
        x -= w
        if x <= 0:
            return item
    return weighted[-1][0]


def random_selections(rng, mesh, cap):
    """1-4 patch files' face sets and a description of how each was made."""
    nfiles = _pick(rng, [(1, 50), (2, 30), (3, 12), (4, 8)])
    keep_overlap = rng.random() < 0.05
    files, notes, taken = [], [], set()
    for i in range(nfiles):
        for _ in range(5):  # a file left empty by the files before it is made again
            faces, parts = set(), []
            for _ in range(_pick(rng, [(1, 70), (2, 20), (3, 10)])):
                region, note = _region(rng, mesh, _pick(rng, REGION_KINDS), cap)
                faces |= region
                parts.append(note)
            if not keep_overlap:
                faces -= taken
            if faces:
                break
        taken |= faces
        files.append(sorted(faces))
        notes.append(" + ".join(parts))
    if keep_overlap:
        notes.append("overlaps kept")
    return files, notes


def selection_text(rng, faces, prefix="f", obj_name="pMesh"):
    """A patch (or pin) file for `faces`: plain ids, ranges, Maya strings, commas, comments."""
    runs = []
    for f in sorted(faces):
        if runs and runs[-1][1] == f - 1:
            runs[-1][1] = f
        else:
            runs.append([f, f])
    rng.shuffle(runs)
    style = rng.choice(["plain", "ranges", "maya", "mixed"])
    tokens = []
    for a, b in runs:
        s = style if style != "mixed" else rng.choice(["plain", "ranges", "maya"])
        if s == "plain" or (s == "ranges" and a == b and rng.random() < 0.5):
            tokens += [str(f) for f in range(a, b + 1)]
        elif s == "ranges":
            tokens.append(f"{a}-{b}")
        else:
            name = obj_name + "." if rng.random() < 0.7 else ""
            tokens.append(f"{name}{prefix}[{a}:{b}]" if a != b or rng.random() < 0.5
                          else f"{name}{prefix}[{a}]")
    lines, line = ["# made by tests/property"], []
    for t in tokens:
        line.append(t)
        if len(line) >= rng.randint(1, 12):
            lines.append(rng.choice([" ", ", ", "\t"]).join(line) +
                         (rng.choice(["", "  # note"]) if rng.random() < 0.2 else ""))
            line = []
    if line:
        lines.append(" ".join(line))
    return "\n".join(lines) + rng.choice(["\n", "", "\n\n"])


# ---- frames -------------------------------------------------------------------------------------

def _rotation(rng):
    q = np.array([rng.gauss(0, 1) for _ in range(4)])
    q /= np.linalg.norm(q)
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def _axis_angle(axis, angle):
    axis = axis / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * (k @ k)


def deform(rng, positions, kind):
    """A deformed copy of `positions` and whether it is degenerate (collapsed, flattened,
    folded: a frame the paper's nets may refuse)."""
    p = positions.copy()
    c = p.mean(axis=0)
    d = max(diagonal(p), 1e-12)
    if kind == "identity":
        return p, False
    if kind == "bend":
        a = np.array([rng.gauss(0, 1) for _ in range(3)])
        a /= np.linalg.norm(a)
        perp = np.cross(a, np.array([rng.gauss(0, 1) for _ in range(3)]))
        if np.linalg.norm(perp) < 1e-9:
            perp = np.cross(a, [1.0, 0.0, 0.0])
        angle = rng.uniform(-2.0, 2.0)
        width = rng.uniform(0.02, 0.3) * d
        s = (p - c) @ a
        t = np.clip((s / width + 1) / 2, 0, 1)
        t = t * t * (3 - 2 * t)
        out = np.empty_like(p)
        for i in range(len(p)):
            out[i] = c + _axis_angle(perp, angle * t[i]) @ (p[i] - c)
        return out, False
    if kind == "twist":
        a = np.array([rng.gauss(0, 1) for _ in range(3)])
        a /= np.linalg.norm(a)
        k = rng.uniform(-3, 3) / d
        out = np.empty_like(p)
        s = (p - c) @ a
        for i in range(len(p)):
            out[i] = c + _axis_angle(a, k * s[i]) @ (p[i] - c)
        return out, False
    if kind == "noise":
        amp = rng.uniform(0.001, 0.08) * d
        for _ in range(rng.randint(1, 4)):
            w = np.array([rng.gauss(0, 1) for _ in range(3)]) * rng.uniform(1, 12) / d
            direction = np.array([rng.gauss(0, 1) for _ in range(3)])
            p = p + amp * np.sin(p @ w + rng.uniform(0, 6.3))[:, None] * direction
        return p, False
    if kind == "rigid":
        return (p - c) @ _rotation(rng).T * rng.choice([1.0, 1.0, 0.5, 3.0]) + \
            rng.uniform(-1, 1) * d, False
    if kind == "jitter":
        scale = rng.choice([1e-9, 1e-4, 1e-2]) * d
        return p + scale * np.random.default_rng(rng.randrange(2**32)).standard_normal(p.shape), False
    if kind == "collapse":
        centre = p[rng.randrange(len(p))]
        radius = rng.uniform(0.05, 0.6) * d
        r = np.linalg.norm(p - centre, axis=1)
        factor = rng.choice([0.0, 0.0, 1e-12, 0.01])
        inside = r < radius
        p[inside] = centre + factor * (p[inside] - centre)
        return p, True
    if kind == "flatten":
        n = np.array([rng.gauss(0, 1) for _ in range(3)])
        n /= np.linalg.norm(n)
        return p - np.outer((p - c) @ n, n), True
    if kind == "fold":
        n = np.array([rng.gauss(0, 1) for _ in range(3)])
        n /= np.linalg.norm(n)
        s = (p - c) @ n
        return p - 2 * np.outer(np.maximum(s, 0), n), True
    if kind == "signed_zero":
        # zeros made -0.0 and a few coordinates subnormal: bits a rewrite must not lose
        g = np.random.default_rng(rng.randrange(2**32))
        zero = p == 0
        p = np.where(zero, -0.0, p)
        pick = zero & (g.random(p.shape) < 0.3)
        p[pick] = np.where(g.random(int(pick.sum())) < 0.5, 5e-324, -2.5e-310)
        return p, False
    if kind == "spike":
        # a few vertices thrown far off (a broken rig): spikes, slivers, huge triangles
        for _ in range(rng.randint(1, 3)):
            v = rng.randrange(len(p))
            p[v] = p[v] + np.array([rng.gauss(0, 1) for _ in range(3)]) * d * rng.choice([0.5, 10, 1e3])
        return p, False
    if kind == "point":
        return np.repeat(p[rng.randrange(len(p))][None], len(p), axis=0), True
    raise ValueError(kind)


FRAME_KINDS = [("bend", 30), ("noise", 20), ("twist", 10), ("identity", 8), ("rigid", 8),
               ("jitter", 6), ("collapse", 6), ("flatten", 4), ("fold", 5), ("point", 2),
               ("signed_zero", 3), ("spike", 4)]


def random_frame(rng, positions):
    kinds = [_pick(rng, FRAME_KINDS) for _ in range(_pick(rng, [(1, 70), (2, 25), (3, 5)]))]
    degenerate = False
    p = positions
    for k in kinds:
        p, deg = deform(rng, p, k)
        degenerate |= deg
    if not np.all(np.isfinite(p)):
        p, degenerate, kinds = positions.copy(), False, ["identity"]
    return p, degenerate, "+".join(kinds)

