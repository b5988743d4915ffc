"""What the patch files select, worked out independently of skinslide: edge-connected components
per patch file, their boundary loops and free vertices, and whether the selection must be refused
(README "Patch files", tests/bad_inputs: shared faces, non-manifold edges, flipped faces, bow-tie
vertices, closed components, a vertex inside one patch touching another)."""
from collections import defaultdict


class Refusal(Exception):
    """The selection must be refused (exit 3); the text says why, for the failure report."""


class Component:
    def __init__(self, selection, faces, vertices, boundary, loops):
        self.selection = selection
        self.faces = faces            # mesh face ids, ascending
        self.vertices = vertices      # mesh vertex ids, ascending
        self.boundary = boundary      # set of vertices on a boundary edge
        self.loops = loops            # boundary loops, each in the faces' direction
        self.interior = [v for v in vertices if v not in boundary]


def _find(parent, a):
    root = a
    while parent[root] != root:
        root = parent[root]
    while parent[a] != root:
        parent[a], a = root, parent[a]
    return root


def _join(parent, a, b):
    a, b = _find(parent, a), _find(parent, b)
    if a != b:
        parent[max(a, b)] = min(a, b)


def split_selection(faces, selected, index):
    """One patch file's faces (sorted, unique) -> its components; raises Refusal."""
    sel = sorted(set(selected))
    corner_start = [0]
    for f in sel:
        poly = faces[f]
        if len(set(poly)) != len(poly):
            raise Refusal(f"patch file {index}: face {f} uses a vertex twice")
        corner_start.append(corner_start[-1] + len(poly))
    edges = defaultdict(list)  # (lo, hi) -> [(position in sel, slot, from)]
    for i, f in enumerate(sel):
        poly = faces[f]
        n = len(poly)
        for k in range(n):
            u, v = poly[k], poly[(k + 1) % n]
            edges[(min(u, v), max(u, v))].append((i, k, u))
    face_parent = list(range(len(sel)))
    corner_parent = list(range(corner_start[-1]))
    boundary_half_edges = []  # (position in sel, from, to)

    def corner(i, slot):
        n = corner_start[i + 1] - corner_start[i]
        return corner_start[i] + slot % n

    for (lo, hi), uses in edges.items():
        if len(uses) > 2:
            raise Refusal(f"patch file {index}: edge ({lo}, {hi}) in {len(uses)} faces")
        if len(uses) == 1:
            i, k, u = uses[0]
            boundary_half_edges.append((i, u, hi if u == lo else lo))
            continue
        (a, ka, ua), (b, kb, ub) = uses
        if ua == ub:
            raise Refusal(f"patch file {index}: edge ({lo}, {hi}) traversed the same way twice")
        _join(face_parent, a, b)
        _join(corner_parent, corner(a, ka), corner(b, kb + 1))
        _join(corner_parent, corner(a, ka + 1), corner(b, kb))
    comp_of = {}
    comp_faces = defaultdict(list)
    for i in range(len(sel)):
        r = _find(face_parent, i)
        c = comp_of.setdefault(r, len(comp_of))
        comp_faces[c].append(i)
    comps = []
    for c in range(len(comp_of)):
        members = comp_faces[c]
        fans = defaultdict(set)
        for i in members:
            poly = faces[sel[i]]
            for k, v in enumerate(poly):
                fans[v].add(_find(corner_parent, corner_start[i] + k))
        for v, roots in fans.items():
            if len(roots) > 1:
                raise Refusal(f"patch file {index}: vertex {v} is a bow-tie ({len(roots)} fans)")
        member_set = set(members)
        half = [(u, w) for i, u, w in boundary_half_edges if i in member_set]
        if not half:
            raise Refusal(f"patch file {index}: component with face {sel[members[0]]} is closed")
        boundary = {u for u, _ in half} | {w for _, w in half}
        nxt = {u: w for u, w in half}
        loops, seen = [], set()
        for u, _ in sorted(half):
            if u in seen:
                continue
            loop = [u]
            seen.add(u)
            w = nxt[u]
            while w != u:
                loop.append(w)
                seen.add(w)
                w = nxt[w]
            loops.append(loop)
        corners = sum(len(faces[sel[i]]) for i in members)
        edges = (corners + sum(len(loop) for loop in loops)) // 2
        if len(fans) - edges + len(members) != 2 - len(loops):
            raise Refusal(f"patch file {index}: component with face {sel[members[0]]} "
                          "is not a disk with holes (it has a handle)")
        comps.append(Component(index, [sel[i] for i in members], sorted(fans), boundary, loops))
    return comps


def patch_components(faces, selections):
    """Every patch file's components, in skinslide's order (smallest vertex, then first face);
    raises Refusal when the selection must be refused."""
    owner = {}
    for s, sel in enumerate(selections):
        for f in set(sel):
            if f in owner:
                raise Refusal(f"face {f} in patch files {owner[f]} and {s}")
            owner[f] = s
    comps = []
    for s, sel in enumerate(selections):
        comps.extend(split_selection(faces, sel, s))
    roles = defaultdict(list)
    for c in comps:
        for v in c.vertices:
            roles[v].append(v in c.boundary)
    for v, r in roles.items():
        if len(r) > 1 and not all(r):
            raise Refusal(f"vertex {v} inside one patch touches another")
    comps.sort(key=lambda c: (c.vertices[0], c.faces[0]))
    return comps


class MeshTopology:
    """Face adjacency of a mesh, for growing regions."""

    def __init__(self, faces):
        self.faces = faces
        edge_faces = defaultdict(list)
        vertex_faces = defaultdict(list)
        for f, poly in enumerate(faces):
            n = len(poly)
            for k in range(n):
                u, v = poly[k], poly[(k + 1) % n]
                edge_faces[(min(u, v), max(u, v))].append(f)
                vertex_faces[u].append(f)
        self.neighbours = [[] for _ in faces]
        for fs in edge_faces.values():
            for a in fs:
                for b in fs:
                    if a != b:
                        self.neighbours[a].append(b)
        self.vertex_faces = vertex_faces
        # edge-connected components of the whole mesh
        comp = [-1] * len(faces)
        self.components = []
        for f in range(len(faces)):
            if comp[f] >= 0:
                continue
            c = len(self.components)
            stack, members = [f], []
            comp[f] = c
            while stack:
                g = stack.pop()
                members.append(g)
                for h in self.neighbours[g]:
                    if comp[h] < 0:
                        comp[h] = c
                        stack.append(h)
            self.components.append(sorted(members))
        self.component_of = comp

    def grow(self, rng, seed, size, allowed=None):
        """Faces reached from `seed` across edges in a randomised breadth-first order."""
        region = {seed}
        frontier = [seed]
        while frontier and len(region) < size:
            k = rng.randrange(len(frontier)) if rng.random() < 0.3 else 0
            f = frontier.pop(k)
            nbrs = list(self.neighbours[f])
            rng.shuffle(nbrs)
            for g in nbrs:
                if g not in region and (allowed is None or g in allowed):
                    region.add(g)
                    frontier.append(g)
                    if len(region) >= size:
                        break
        return region
