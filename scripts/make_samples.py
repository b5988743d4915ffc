#!/usr/bin/env python3
"""Generate skinslide's sample data: two small cases used by the demo and the tests.

    python3 scripts/make_samples.py data

elbow: open tube (radius 1, length 8 along z, 32 quads around, 32 along), bent
       at z = 4 about the x axis by two-bone linear blend skinning (bone-2
       weight = smoothstep over z in [2.5, 5.5]); frames at 0, 22.5, 45, 67.5
       and 90 degrees (frame 1 has the bind's v lines exactly).  Patch = the faces
       whose centre lies in the middle third, z in [8/3, 16/3]: a band with two
       boundary loops of equal length.
face:  32 x 32 quad grid on a spherical cap squashed in x, with two 6 x 3 quad
       eye holes; four rows are split into triangles.  Frames apply a smooth
       nonlinear displacement (cubic stretch of the +x side, shear, bump) with
       t = 0.25, 0.5, 0.75, 1.  Patch = all faces (one outer loop, two holes).

Writes DIR/<case>/{bind.obj, patch.txt, patch_plain.txt, frames/<case>.NNNN.obj}
and DIR/README.md; for the README's examples, DIR/elbow also gets the frames as a
point cache (elbow.pc2), the tube as a rigged glTF (rig.glb, rig_patch.txt), the
patch in two halves (patch_lower.txt, patch_upper.txt), slide weights and pins.  Python 3 standard library only; no randomness, so every run
writes the same bytes.  Positions are rounded to kDecimals decimals (as an
exporter's fixed precision would) and written with repr(float), so the file
value is the exact value used; bind and frames share their vt, s and f lines.
"""

import json
import math
import os
import struct
import sys

kDecimals = 9  # position precision in the OBJ files
kUvDecimals = 6  # texture-coordinate precision


# ----------------------------------------------------------------------------
# Small vector arithmetic (tuples of 3 floats)
# ----------------------------------------------------------------------------

def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def scale(s, a):
    return (s * a[0], s * a[1], s * a[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(dot(a, a))


def smoothstep(t):
    t = min(max(t, 0.0), 1.0)
    return t * t * (3.0 - 2.0 * t)


def quantise(p, decimals):
    # + 0.0 turns -0.0 into 0.0 so that "-0.0" never appears in a file
    return tuple(round(x, decimals) + 0.0 for x in p)


# ----------------------------------------------------------------------------
# Writing
# ----------------------------------------------------------------------------

def write_text(path, text):
    with open(path, "w", encoding="ascii", newline="\n") as fh:
        fh.write(text)


def obj_text(header, name, V, VT, faces):
    """OBJ text: header comment, o, v, vt, s off, then f v/vt lines (1-based).

    faces: list of faces, each a list of (vertex index, texcoord index), 0-based.
    """
    out = ["# %s\n" % header, "o %s\n" % name]
    out += ["v %r %r %r\n" % p for p in V]
    out += ["vt %r %r\n" % t for t in VT]
    out.append("s off\n")
    for f in faces:
        out.append("f " + " ".join("%d/%d" % (v + 1, t + 1) for v, t in f) + "\n")
    return "".join(out)


def patch_text(comment_lines, parts):
    """Patch file text: '#' comment lines, then one line per part (already formatted)."""
    return "".join("# %s\n" % c for c in comment_lines) + "".join(p + "\n" for p in parts)


def plain_patch_text(comment, ids):
    lines = ["# %s\n" % comment]
    for i in range(0, len(ids), 16):
        lines.append(" ".join(str(x) for x in ids[i:i + 16]) + "\n")
    return "".join(lines)


# ----------------------------------------------------------------------------
# Checks and counts
# ----------------------------------------------------------------------------

def boundary_loop_count(faces, patch):
    """Number of boundary loops of the selected faces (edges used by one face)."""
    count = {}
    for fi in patch:
        f = faces[fi]
        for k in range(len(f)):
            a, b = f[k][0], f[(k + 1) % len(f)][0]
            e = (min(a, b), max(a, b))
            count[e] = count.get(e, 0) + 1
    assert all(c <= 2 for c in count.values()), "non-manifold edge"
    adj = {}
    for (a, b), c in count.items():
        if c == 1:
            adj.setdefault(a, []).append(b)
            adj.setdefault(b, []).append(a)
    assert all(len(n) == 2 for n in adj.values()), "boundary vertex on several loops"
    seen = set()
    loops = 0
    for start in sorted(adj):
        if start in seen:
            continue
        loops += 1
        stack = [start]
        while stack:
            v = stack.pop()
            if v not in seen:
                seen.add(v)
                stack.extend(adj[v])
    return loops


def check_outward(V, faces, outward):
    """Every face's Newell normal points along outward(centre)."""
    for f in faces:
        P = [V[v] for v, _ in f]
        n = (0.0, 0.0, 0.0)
        for k in range(len(P)):
            n = add(n, cross(P[k], P[(k + 1) % len(P)]))
        c = scale(1.0 / len(P), sum_points(P))
        assert dot(n, outward(c)) > 0.0, "face not oriented outwards"


def sum_points(P):
    s = (0.0, 0.0, 0.0)
    for p in P:
        s = add(s, p)
    return s


def bbox_extent(V):
    lo = [min(p[k] for p in V) for k in range(3)]
    hi = [max(p[k] for p in V) for k in range(3)]
    return [hi[k] - lo[k] for k in range(3)]


def summary(name, V, faces, patch, frames):
    pv = set(v for fi in patch for v, _ in faces[fi])
    assert all(len(f) in (3, 4) for f in faces)
    return {"name": name, "n_vertices": len(V), "n_faces": len(faces),
            "n_patch_faces": len(patch), "n_patch_vertices": len(pv),
            "n_loops": boundary_loop_count(faces, patch),
            "n_triangles": sum(1 for f in faces if len(f) == 3),
            "n_quads": sum(1 for f in faces if len(f) == 4), "n_frames": len(frames)}


def save_case(root, name, V, VT, faces, frames, patch_file_text, patch, info):
    d = os.path.join(root, name)
    os.makedirs(os.path.join(d, "frames"), exist_ok=True)
    write_text(os.path.join(d, "bind.obj"),
               obj_text("skinslide sample data: %s, bind pose" % name, name, V, VT, faces))
    for k, Vf in enumerate(frames, 1):
        write_text(os.path.join(d, "frames", "%s.%04d.obj" % (name, k)),
                   obj_text("skinslide sample data: %s, frame %d" % (name, k), name, Vf, VT,
                            faces))
    write_text(os.path.join(d, "patch.txt"), patch_file_text)
    write_text(os.path.join(d, "patch_plain.txt"),
               plain_patch_text("%s patch: %d face indices (0-based, OBJ f order)"
                                % (name, len(patch)), patch))
    return info


# ----------------------------------------------------------------------------
# elbow
# ----------------------------------------------------------------------------

def case_elbow(root):
    n_around, n_along, radius, length = 32, 32, 1.0, 8.0
    joint = (0.0, 0.0, length / 2)
    blend = (2.5, 5.5)
    angles = [0.0, 22.5, 45.0, 67.5, 90.0]

    # vertex (ring k, column i) = k * n_around + i; z = length * k / n_along is exact
    V = []
    for k in range(n_along + 1):
        z = length * k / n_along
        for i in range(n_around):
            th = 2.0 * math.pi * i / n_around
            V.append(quantise((radius * math.cos(th), radius * math.sin(th), z), kDecimals))
    # texcoords (ring k, column i), i = 0..n_around: the seam column is doubled
    VT = [(i / n_around, k / n_along) for k in range(n_along + 1) for i in range(n_around + 1)]
    faces = []
    for k in range(n_along):
        for i in range(n_around):
            i1 = (i + 1) % n_around
            faces.append([(k * n_around + i, k * (n_around + 1) + i),
                          (k * n_around + i1, k * (n_around + 1) + i + 1),
                          ((k + 1) * n_around + i1, (k + 1) * (n_around + 1) + i + 1),
                          ((k + 1) * n_around + i, (k + 1) * (n_around + 1) + i)])
    check_outward(V, faces, lambda c: (c[0], c[1], 0.0))

    lo, hi = length / 3, 2 * length / 3
    patch = []
    for fi, f in enumerate(faces):
        zc = sum(V[v][2] for v, _ in f) / len(f)
        if lo <= zc <= hi:
            patch.append(fi)
    assert patch == list(range(patch[0], patch[-1] + 1)), "elbow patch is one run of faces"

    frames = []
    for a in angles:
        c, s = math.cos(math.radians(a)), math.sin(math.radians(a))
        Vf = []
        for p in V:
            w = smoothstep((p[2] - blend[0]) / (blend[1] - blend[0]))
            q = sub(p, joint)
            rotated = add((q[0], c * q[1] - s * q[2], s * q[1] + c * q[2]), joint)
            # p + w (rotated - p): exactly p where the rotation is the identity
            Vf.append(quantise(add(p, scale(w, sub(rotated, p))), kDecimals))
        frames.append(Vf)
    assert frames[0] == V, "frame 1 is the bind pose"

    # one of each patch syntax: plain integers, an inclusive range, a Maya component string
    first, last = patch[0], patch[-1]
    parts = [" ".join(str(i) for i in range(first, first + 8)),
             "%d-%d" % (first + 8, first + 159),
             "elbow.f[%d:%d]" % (first + 160, last)]
    text = patch_text(["elbow patch: the middle third of the tube, faces %d-%d (%d faces)"
                       % (first, last, len(patch)),
                       "0-based indices in OBJ f order; plain, a-b and name.f[a:b] are inclusive"],
                      parts)
    info = summary("elbow", V, faces, patch, frames)
    info["max_displacement"] = max(norm(sub(p, q)) for p, q in zip(frames[-1], V))
    save_case(root, "elbow", V, VT, faces, frames, text, patch, info)
    d = os.path.join(root, "elbow")
    write_bytes(os.path.join(d, "elbow.pc2"), pc2_bytes(frames, 1.0))
    write_bytes(os.path.join(d, "rig.glb"),
                elbow_rig_glb(V, faces, joint, blend, angles, n_around))
    write_text(os.path.join(d, "rig_patch.txt"),
               patch_text(["rig.glb's patch: the elbow patch's quads as triangles (two a quad,",
                           "in face order: quad q is triangles 2q and 2q + 1)"],
                          ["%d-%d" % (2 * first, 2 * last + 1)]))
    half = first + len(patch) // 2
    write_text(os.path.join(d, "patch_lower.txt"),
               patch_text(["the elbow patch's lower half: a band of its own"],
                          ["%d-%d" % (first, half - 1)]))
    write_text(os.path.join(d, "patch_upper.txt"),
               patch_text(["the elbow patch's upper half: a band of its own"],
                          ["%d-%d" % (half, last)]))
    # Slide weights: 1 on the side facing +x, fading to 0 on the side facing -x.
    write_text(os.path.join(d, "weights.txt"),
               "# slide weight per vertex, in vertex order\n" +
               "".join("%r\n" % round(0.5 + 0.5 * p[0], 4) for p in V))
    # Pins: the two vertices of the middle ring (the joint) on the bend's inside and outside.
    ring = n_along // 2 * n_around
    write_text(os.path.join(d, "pins.txt"),
               "# vertices that do not slide: ring %d (z = 4) at y = 1 and y = -1\n%d %d\n"
               % (n_along // 2, ring + n_around // 4, ring + 3 * n_around // 4))
    return info


# ----------------------------------------------------------------------------
# elbow as a point cache and as a rigged glTF (the README's examples)
# ----------------------------------------------------------------------------

def write_bytes(path, data):
    with open(path, "wb") as fh:
        fh.write(data)


def pc2_bytes(frames, start_frame):
    """The frames as a PC2 point cache (lib/io/README.md): frame start_frame + k for sample k,
    float32 coordinates, as Blender's exporter writes one."""
    out = [struct.pack("<12siiffi", b"POINTCACHE2\0", 1, len(frames[0]), start_frame, 1.0,
                       len(frames))]
    out += [struct.pack("<3f", *p) for f in frames for p in f]
    return b"".join(out)


def elbow_rig_glb(V, faces, joint, blend, angles, n_around):
    """The elbow tube as a skinned glTF (GLB): joint 0 "upper" at the origin, joint 1 "lower" at
    the elbow's joint, vertex weights as the frames were made (lower = smoothstep over z in
    `blend`), and a clip "bend" turning "lower" about x through `angles`, one key a quarter
    second (LINEAR). Each quad is two triangles (a b c, a c d); no UVs, so no vertex is split."""
    bin_parts, views, accessors = [], [], []

    def add(data, count, component, kind, target=None, minmax=None):
        offset = sum(len(b) for b in bin_parts)
        bin_parts.append(data + b"\0" * (-len(data) % 4))
        view = {"buffer": 0, "byteOffset": offset, "byteLength": len(data)}
        if target:
            view["target"] = target
        views.append(view)
        accessor = {"bufferView": len(views) - 1, "componentType": component, "count": count,
                    "type": kind}
        if minmax:
            accessor["min"], accessor["max"] = minmax
        accessors.append(accessor)
        return len(accessors) - 1

    f32 = [struct.unpack("<f", struct.pack("<f", x))[0] for p in V for x in p]
    lo = [min(f32[k::3]) for k in range(3)]
    hi = [max(f32[k::3]) for k in range(3)]
    position = add(struct.pack("<%df" % len(f32), *f32), len(V), 5126, "VEC3", 34962, (lo, hi))
    weights = [smoothstep((p[2] - blend[0]) / (blend[1] - blend[0])) for p in V]
    joints = add(b"".join(struct.pack("<4B", 0, 1, 0, 0) for _ in V), len(V), 5121, "VEC4", 34962)
    weight = add(b"".join(struct.pack("<4f", 1.0 - w, w, 0.0, 0.0) for w in weights), len(V),
                 5126, "VEC4", 34962)
    triangles = [t for f in faces for t in ((f[0][0], f[1][0], f[2][0]), (f[0][0], f[2][0], f[3][0]))]
    indices = add(struct.pack("<%dH" % (3 * len(triangles)), *[v for t in triangles for v in t]),
                  3 * len(triangles), 5123, "SCALAR", 34963)
    identity = [1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0]
    inverse_binds = add(struct.pack("<32f", *(identity + [0, 0, 0, 1.0]),
                                    *(identity + [-joint[0], -joint[1], -joint[2], 1.0])),
                        2, 5126, "MAT4")
    times = [0.25 * k for k in range(len(angles))]
    key_times = add(struct.pack("<%df" % len(times), *times), len(times), 5126, "SCALAR",
                    minmax=([times[0]], [times[-1]]))
    turns = [(math.sin(math.radians(a) / 2), 0.0, 0.0, math.cos(math.radians(a) / 2))
             for a in angles]
    rotations = add(b"".join(struct.pack("<4f", *q) for q in turns), len(turns), 5126, "VEC4")
    binary = b"".join(bin_parts)
    document = {
        "asset": {"version": "2.0", "generator": "skinslide scripts/make_samples.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 2]}],
        "nodes": [{"name": "upper", "children": [1]},
                  {"name": "lower", "translation": list(joint)},
                  {"name": "elbow", "mesh": 0, "skin": 0}],
        "skins": [{"joints": [0, 1], "inverseBindMatrices": inverse_binds}],
        "meshes": [{"name": "elbow", "primitives": [{
            "attributes": {"POSITION": position, "JOINTS_0": joints, "WEIGHTS_0": weight},
            "indices": indices}]}],
        "animations": [{"name": "bend",
                        "samplers": [{"input": key_times, "output": rotations}],
                        "channels": [{"sampler": 0, "target": {"node": 1, "path": "rotation"}}]}],
        "buffers": [{"byteLength": len(binary)}],
        "bufferViews": views,
        "accessors": accessors,
    }
    text = json.dumps(document, separators=(",", ":"), sort_keys=True).encode("ascii")
    text += b" " * (-len(text) % 4)
    chunks = (struct.pack("<I4s", len(text), b"JSON") + text +
              struct.pack("<I4s", len(binary), b"BIN\0") + binary)
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


# ----------------------------------------------------------------------------
# face
# ----------------------------------------------------------------------------

def face_displacement(p):
    """Smooth nonlinear field: cubic stretch of the +x side, shear, a bump."""
    x, y, _ = p
    return (0.36 * ((x + 1.0) / 2.0) ** 3,
            0.12 * math.sin(math.pi * x) * y,
            0.18 * math.exp(-((x - 0.5) ** 2 + (y + 0.3) ** 2) / 0.1))


def cap_point(px, py):
    """Plane point -> spherical cap: equidistant azimuthal map, 81 degrees per unit
    radius, squashed in x."""
    r = math.hypot(px, py)
    al = math.atan2(py, px)
    phi = r * (math.pi / 2) * 0.9
    return (0.85 * math.sin(phi) * math.cos(al), math.sin(phi) * math.sin(al), math.cos(phi))


def border_balanced_half_width(n, half_y):
    """Grid half-width in x for which the bottom and left sides of the lifted n x n
    grid have the same 3D length.

    All four sides are then equally long, so the arc-length corners of the unit
    square (0, 1/4, 1/2, 3/4 of the outer loop) fall on the grid's corners and no
    quad is pressed flat against a side of the square.
    """
    def side(points):
        return sum(norm(sub(points[k + 1], points[k])) for k in range(len(points) - 1))

    def excess(hx):
        bottom = side([cap_point(hx * (2.0 * i / n - 1.0), -half_y) for i in range(n + 1)])
        left = side([cap_point(-hx, half_y * (2.0 * j / n - 1.0)) for j in range(n + 1)])
        return bottom - left

    lo, hi = 0.5 * half_y, 2.0 * half_y
    assert excess(lo) < 0.0 < excess(hi)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if excess(mid) < 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def case_face(root):
    n = 32  # quads per side
    half_y = 0.65  # grid half-height in the plane before lifting
    eye_cols = [(7, 12), (19, 24)]  # inclusive quad columns, symmetric about the centre
    eye_rows = (19, 21)  # inclusive quad rows, in the upper half
    tri_rows = (3, 6)  # quad rows split into two triangles

    def in_eye(i, j):
        return eye_rows[0] <= j <= eye_rows[1] and any(a <= i <= b for a, b in eye_cols)

    # quads between a hole and the outer border or the other hole: at least 2
    assert eye_cols[0][1] - eye_cols[0][0] == eye_cols[1][1] - eye_cols[1][0]
    assert eye_cols[0][0] == n - 1 - eye_cols[1][1], "eyes symmetric"
    assert eye_rows[0] >= n // 2, "eyes in the upper half"
    margin = min(eye_cols[0][0], n - 1 - eye_cols[1][1], eye_rows[0], n - 1 - eye_rows[1],
                 eye_cols[1][0] - eye_cols[0][1] - 1)
    assert margin >= 2, "holes too close to the border or to each other"

    def gid(i, j):  # grid vertex (column i, row j)
        return j * (n + 1) + i

    grid_faces = []
    for j in range(n):
        for i in range(n):
            if in_eye(i, j):
                continue
            a, b, c, d = gid(i, j), gid(i + 1, j), gid(i + 1, j + 1), gid(i, j + 1)
            if tri_rows[0] <= j <= tri_rows[1]:
                if (i + j) % 2 == 0:
                    grid_faces += [[a, b, c], [a, c, d]]
                else:
                    grid_faces += [[a, b, d], [b, c, d]]
            else:
                grid_faces.append([a, b, c, d])

    # drop the vertices inside the holes, keep grid order for the rest
    used = sorted(set(v for f in grid_faces for v in f))
    remap = {g: k for k, g in enumerate(used)}
    faces = [[(remap[g], remap[g]) for g in f] for f in grid_faces]

    hx = border_balanced_half_width(n, half_y)
    V, VT = [], []
    for g in used:
        i, j = g % (n + 1), g // (n + 1)
        u, v = i / n, j / n
        V.append(quantise(cap_point(hx * (2.0 * u - 1.0), half_y * (2.0 * v - 1.0)), kDecimals))
        VT.append(quantise((u, v, 0.0), kUvDecimals)[:2])
    # the cap's centre of curvature is the origin (before the x squash, which keeps signs)
    check_outward(V, faces, lambda c: c)

    ts = [0.25, 0.5, 0.75, 1.0]
    D = [face_displacement(p) for p in V]
    frames = [[quantise(add(p, scale(t, d)), kDecimals) for p, d in zip(V, D)] for t in ts]

    patch = list(range(len(faces)))
    text = patch_text(["face patch: all %d faces" % len(faces),
                       "0-based indices in OBJ f order; the range a-b is inclusive"],
                      ["0-%d" % (len(faces) - 1)])
    info = summary("face", V, faces, patch, frames)
    info["max_displacement"] = max(norm(sub(p, q)) for p, q in zip(frames[-1], V))
    info["extent"] = max(bbox_extent(V))
    info["grid"] = n
    info["eye"] = (eye_cols[0][1] - eye_cols[0][0] + 1, eye_rows[1] - eye_rows[0] + 1)
    info["margin"] = margin
    info["tri_rows"] = tri_rows
    return save_case(root, "face", V, VT, faces, frames, text, patch, info)


# ----------------------------------------------------------------------------
# README
# ----------------------------------------------------------------------------

def readme_text(infos):
    e, f = infos["elbow"], infos["face"]
    rows = []
    for i in (e, f):
        rows.append("| %s | %d | %d | %d | %d | %d | %d | %d | %d |"
                    % (i["name"], i["n_vertices"], i["n_faces"], i["n_quads"], i["n_triangles"],
                       i["n_patch_faces"], i["n_patch_vertices"], i["n_loops"], i["n_frames"]))
    return """# skinslide sample data

Two small cases for the demo command and the tests, written by
`scripts/make_samples.py`.  Regenerate them (same bytes every run, Python 3
standard library only) with

    python3 scripts/make_samples.py data

Each case folder holds `bind.obj`, `frames/<case>.NNNN.obj`, `patch.txt` and
`patch_plain.txt`.  A frame has the bind's vertex order and the same `vt`, `s`
and `f` lines; only the `v` lines differ.  OBJ files have a comment line, an
`o` line, `v`, `vt`, `s off` and `f v/vt` lines (no normals, no materials).
Positions are rounded to %d decimals, texture coordinates to %d.

| case | vertices | faces | quads | triangles | patch faces | patch vertices | boundary loops | frames |
|---|---|---|---|---|---|---|---|---|
%s

## elbow

An open tube, radius 1 and length 8 along z, 32 quads around and 32 along,
bent at z = 4 about the x axis by two-bone linear blend skinning (bone-2
weight = smoothstep over z in [2.5, 5.5]).  Frames 1-5 are at 0, 22.5, 45,
67.5 and 90 degrees; frame 1 is the bind pose (identical `v` lines).  The
texture coordinates are a cylindrical unwrap with a seam, so the tube has
more `vt` than `v` lines.

The patch is the band of faces whose centre lies in the middle third of the
tube (z in [8/3, 16/3]): two boundary loops of exactly equal length, so the
outer-loop tie rule decides which one is the square.  `patch.txt` writes it in
every syntax skinslide reads: `#` comments, plain indices, an inclusive range
`a-b` and a Maya component string `name.f[a:b]`.  `patch_plain.txt` holds the
same faces as plain whitespace-separated integers.

## face

A face-like patch: a %d x %d quad grid lifted onto a spherical cap squashed in
x, with two eye holes (%d x %d quads each, symmetric in the upper half, at least
%d quads from the border and from each other).  Quad rows %d-%d are split into
two triangles each, alternating the diagonal, so quads and triangles are both
present.  Faces are oriented with their normals outwards.  Frames 1-4 apply a
smooth nonlinear displacement (a cubic stretch of the +x side, a shear and a
Gaussian bump) scaled by t = 0.25, 0.5, 0.75 and 1; the largest displacement
is %.3f, %.0f%% of the patch's largest extent (%.3f).

The patch is every face: one outer loop and two hole loops.  `patch.txt`
selects them with one range `0-%d`; `patch_plain.txt` lists them one by one.

## The README's examples

Beside the elbow case, for the top-level README's commands (`tests/cli/
readme_examples.sh` runs every one of them):

- `elbow.pc2`: frames 1-5 as one PC2 point cache (sample k is frame k + 1,
  float32), as Blender's exporter writes one.
- `rig.glb`: the tube as a rigged glTF: joints `upper` (at the origin) and
  `lower` (at the joint, z = 4), the frames' weights, and a clip `bend` turning
  `lower` about x through the frames' five angles, a key every 0.25 s (no UVs,
  so no vertex is split).  `rig_patch.txt`: the patch's quads as its
  triangles (quad q is triangles 2q and 2q + 1).
- `patch_lower.txt`, `patch_upper.txt`: the patch cut into two bands.
- `weights.txt`: a slide weight per vertex, 1 on the side facing +x fading to
  0 on the side facing -x; `pins.txt`: two vertices of the middle ring.

## License

Generated by skinslide's own script, `scripts/make_samples.py`; no third-party
data.  The files are distributed under the same license as skinslide.
""" % (kDecimals, kUvDecimals, "\n".join(rows), f["grid"], f["grid"], f["eye"][0],
       f["eye"][1], f["margin"], f["tri_rows"][0], f["tri_rows"][1], f["max_displacement"],
       100.0 * f["max_displacement"] / f["extent"], f["extent"], f["n_faces"] - 1)


def main(argv):
    if len(argv) != 2:
        sys.stderr.write("usage: make_samples.py OUTDIR\n")
        return 2
    root = argv[1]
    os.makedirs(root, exist_ok=True)
    infos = {"elbow": case_elbow(root), "face": case_face(root)}
    write_text(os.path.join(root, "README.md"), readme_text(infos))
    for i in infos.values():
        sys.stdout.write("%s: %d vertices, %d faces, %d patch faces, %d patch vertices, "
                         "%d loops, %d frames\n"
                         % (i["name"], i["n_vertices"], i["n_faces"], i["n_patch_faces"],
                            i["n_patch_vertices"], i["n_loops"], i["n_frames"]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
