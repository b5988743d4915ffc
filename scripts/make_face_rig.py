#!/usr/bin/python3
"""Builds a facial rig in glTF from the shared ICT FaceKit OBJs: the neutral head as the base
mesh, four expressions as morph targets, and three clips that animate their weights.

    scripts/make_face_rig.py OUT.glb|OUT.gltf [--obj-dir DIR] [--patch PATCH.txt]

The mesh is the head of generic_neutral_mesh.obj: its M_Face faces (OBJ faces 0-9229) and
M_BackHead faces (9230-14033), all quads, as two TRIANGLES primitives in that order. Each quad
(v0 v1 v2 v3) becomes the fan (v0 v1 v2) (v0 v2 v3), so OBJ face f < 14034 is glTF triangles
2f and 2f+1, and the face region is triangles 0-18459 (--patch writes that patch file). A
primitive's vertices are its (position, UV) pairs in order of first use, split at UV seams as
exporters do (skinslide welds them back). Attributes: POSITION, NORMAL (area-weighted, from the
fan triangles), TEXCOORD_0 (OBJ v flipped to glTF's 1 - v).

Morph targets, in this order: jawOpen, mouthSmile_L, eyeBlink_L, browInnerUp_L (the order of
scripts/quality.sh). Target POSITION = expression - neutral (the float32 neutral as stored),
NORMAL = the expression's normal - the neutral's; stored sparse (no bufferView) where fewer than
3/4 of a primitive's vertices move, else dense. Weight 1 on one target gives that expression to
float32 precision. mesh.extras.targetNames names them.

Clips (CLIPS below; the node "face" sits under a root scaling centimetres to metres):
  0 "blend"  LINEAR, 0-4 s every 0.5 s: neutral, each expression in turn at 0.5, 1.5, 2.5 and
             3.5 s with half-and-half blends of neighbours at 1, 2 and 3 s, neutral at 4 s
  1 "cubic"  CUBICSPLINE, keys at 0, 1, 2 s with non-zero tangents
  2 "step"   STEP, keys at 0, 0.75, 1.5 s
Python standard library only; a few seconds.
"""
import argparse
import base64
import json
import math
import os
import struct
import sys

EXPRESSIONS = ["jawOpen", "mouthSmile_L", "eyeBlink_L", "browInnerUp_L"]
MATERIALS = ["M_Face", "M_BackHead"]  # the head: OBJ faces 0-9229, then 9230-14033

# name -> (interpolation, key times, per key: the weights (LINEAR, STEP) or
# (in-tangent, value, out-tangent) (CUBICSPLINE)).
CLIPS = [
    ("blend", "LINEAR", [0.5 * k for k in range(9)], [
        (0, 0, 0, 0), (1, 0, 0, 0), (0.5, 0.5, 0, 0), (0, 1, 0, 0), (0, 0.5, 0.5, 0),
        (0, 0, 1, 0), (0, 0, 0.5, 0.5), (0, 0, 0, 1), (0, 0, 0, 0)]),
    ("cubic", "CUBICSPLINE", [0, 1, 2], [
        ((0, 0, 0, 0), (0, 0, 0, 0), (1, 0, 0.5, 0)),
        ((0, 1, 0, 0), (0.5, 0.5, 0, 0), (-0.5, 1, 0, 0.25)),
        ((0, 0, -1, 1), (0, 0, 1, 0.5), (0, 0, 0, 0))]),
    ("step", "STEP", [0, 0.75, 1.5], [(0, 0, 0, 1), (0, 1, 0, 0), (1, 0, 0, 0)]),
]


def weights_at(clip, t):
    """The clip's weights at time t, as glTF 2.0 Appendix C says (clamped outside the keys)."""
    _, interp, times, keys = clip
    value = (lambda k: keys[k][1]) if interp == "CUBICSPLINE" else (lambda k: keys[k])
    if t <= times[0]:
        return list(value(0))
    if t >= times[-1]:
        return list(value(len(times) - 1))
    k = max(i for i in range(len(times)) if times[i] <= t)
    td = times[k + 1] - times[k]
    s = (t - times[k]) / td
    a, b = value(k), value(k + 1)
    if interp == "STEP":
        return list(a)
    if interp == "LINEAR":
        return [(1 - s) * x + s * y for x, y in zip(a, b)]
    out_k, in_k1 = keys[k][2], keys[k + 1][0]
    s2, s3 = s * s, s * s * s
    return [(2 * s3 - 3 * s2 + 1) * p0 + td * (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 +
            td * (s3 - s2) * m1 for p0, m0, p1, m1 in zip(a, out_k, b, in_k1)]


def read_obj(path):
    """Positions, UVs, faces (lists of (v, vt) 0-based, vt -1 when absent), face materials."""
    v, vt, faces, materials = [], [], [], []
    material = None
    with open(path) as f:
        for line in f:
            s = line.split()
            if not s:
                continue
            if s[0] == "v":
                v.append(tuple(float(x) for x in s[1:4]))
            elif s[0] == "vt":
                vt.append(tuple(float(x) for x in s[1:3]))
            elif s[0] == "usemtl":
                material = s[1]
            elif s[0] == "f":
                corners = []
                for c in s[1:]:
                    p = c.split("/")
                    corners.append((int(p[0]) - 1, int(p[1]) - 1 if len(p) > 1 and p[1] else -1))
                faces.append(corners)
                materials.append(material)
    return v, vt, faces, materials


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def fan(face):
    return [(face[0], face[i], face[i + 1]) for i in range(1, len(face) - 1)]


def head_groups(faces, materials):
    """The OBJ face ids of each primitive (MATERIALS), checked to be the OBJ's first faces."""
    groups = []
    for m in MATERIALS:
        ids = [i for i, x in enumerate(materials) if x == m]
        if not ids:
            sys.exit("make_face_rig: no faces with material %s" % m)
        groups.append(ids)
    if groups[0] != list(range(len(groups[0]))) or groups[1][0] != len(groups[0]):
        sys.exit("make_face_rig: the head's faces are not the first ones of the OBJ")
    return groups


def primitive_vertices(faces, ids):
    """A primitive's raw vertices ((v, vt) pairs of OBJ faces `ids`, in order of first use) and
    its fan triangles over them."""
    raw, index, tris = [], {}, []
    for fi in ids:
        corners = []
        for c in faces[fi]:
            if c not in index:
                index[c] = len(raw)
                raw.append(c)
            corners.append(index[c])
        tris += fan(corners)
    return raw, tris


def vertex_normals(pos, faces):
    """Area-weighted normals of the fan triangles, per OBJ vertex (zero where unused)."""
    acc = {}
    for face in faces:
        for a, b, c in fan([x[0] for x in face]):
            pa, pb, pc = pos[a], pos[b], pos[c]
            u = [pb[i] - pa[i] for i in range(3)]
            w = [pc[i] - pa[i] for i in range(3)]
            n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
            for x in (a, b, c):
                s = acc.setdefault(x, [0.0, 0.0, 0.0])
                for i in range(3):
                    s[i] += n[i]
    out = {}
    for x, s in acc.items():
        length = math.sqrt(sum(c * c for c in s))
        out[x] = tuple(c / length for c in s) if length > 0 else (0.0, 0.0, 1.0)
    return out


class Buffer:
    def __init__(self):
        self.data = bytearray()
        self.views = []
        self.accessors = []

    def view(self, payload, target=None):
        while len(self.data) % 4:
            self.data.append(0)
        v = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload)}
        if target is not None:
            v["target"] = target
        self.data += payload
        self.views.append(v)
        return len(self.views) - 1

    def add(self, accessor):
        self.accessors.append(accessor)
        return len(self.accessors) - 1

    def vec(self, rows, n, bounds=False, target=34962):
        a = {"bufferView": self.view(b"".join(struct.pack("<%df" % n, *r) for r in rows), target),
             "componentType": 5126, "count": len(rows), "type": {1: "SCALAR", 2: "VEC2", 3: "VEC3"}[n]}
        if bounds:
            a["min"] = [min(f32(r[i]) for r in rows) for i in range(n)]
            a["max"] = [max(f32(r[i]) for r in rows) for i in range(n)]
        return self.add(a)

    def delta(self, rows, min_max):
        """A morph target attribute: sparse without bufferView when that is smaller."""
        moved = [i for i, r in enumerate(rows) if any(x != 0 for x in r)]
        if not moved or len(moved) * 4 >= len(rows) * 3:  # sparse needs a substitution
            return self.vec(rows, 3, bounds=min_max)
        big = len(rows) > 65535
        a = {"componentType": 5126, "count": len(rows), "type": "VEC3", "sparse": {
            "count": len(moved),
            "indices": {"bufferView": self.view(struct.pack("<%d%s" % (len(moved), "I" if big else "H"),
                                                            *moved)),
                        "componentType": 5125 if big else 5123},
            "values": {"bufferView": self.view(
                b"".join(struct.pack("<3f", *rows[i]) for i in moved))}}}
        if min_max:
            a["min"] = [min(f32(r[i]) for r in rows) for i in range(3)]
            a["max"] = [max(f32(r[i]) for r in rows) for i in range(3)]
        return self.add(a)


def build(obj_dir):
    """The glTF document (JSON dict) and its binary buffer."""
    pos, uv, faces, materials = read_obj(os.path.join(obj_dir, "generic_neutral_mesh.obj"))
    expressions = []
    for name in EXPRESSIONS:
        epos, _, efaces, _ = read_obj(os.path.join(obj_dir, name + ".obj"))
        if len(epos) != len(pos) or [[c[0] for c in f] for f in efaces] != \
                [[c[0] for c in f] for f in faces]:
            sys.exit("make_face_rig: %s.obj does not have the neutral mesh's vertices and faces"
                     % name)
        expressions.append(epos)
    groups = head_groups(faces, materials)
    head = [faces[i] for g in groups for i in g]
    base32 = [tuple(f32(c) for c in p) for p in pos]
    normals = [vertex_normals(pos, head)] + [vertex_normals(e, head) for e in expressions]
    buf = Buffer()
    primitives = []
    for g in groups:
        raw, tris = primitive_vertices(faces, g)
        attributes = {
            "POSITION": buf.vec([base32[v] for v, _ in raw], 3, bounds=True),
            "NORMAL": buf.vec([normals[0][v] for v, _ in raw], 3)}
        if all(t >= 0 for _, t in raw):
            attributes["TEXCOORD_0"] = buf.vec([(uv[t][0], 1 - uv[t][1]) for _, t in raw], 2)
        n = len(raw)
        flat = [i for t in tris for i in t]
        big = n > 65535
        indices = buf.add({
            "bufferView": buf.view(struct.pack("<%d%s" % (len(flat), "I" if big else "H"), *flat),
                                   34963),
            "componentType": 5125 if big else 5123, "count": len(flat), "type": "SCALAR"})
        targets = []
        for e, epos in enumerate(expressions):
            dp = [tuple(epos[v][i] - base32[v][i] for i in range(3)) for v, _ in raw]
            dn = [tuple(normals[e + 1][v][i] - normals[0][v][i] for i in range(3)) for v, _ in raw]
            targets.append({"POSITION": buf.delta(dp, True), "NORMAL": buf.delta(dn, False)})
        primitives.append({"attributes": attributes, "indices": indices, "mode": 4,
                           "targets": targets})
    animations = []
    for name, interp, times, keys in CLIPS:
        t_acc = buf.vec([(t,) for t in times], 1, bounds=True, target=None)
        flat = [w for key in keys for part in (key if interp == "CUBICSPLINE" else (key,))
                for w in part]
        w_acc = buf.vec([(w,) for w in flat], 1, target=None)
        animations.append({"name": name,
                           "samplers": [{"input": t_acc, "output": w_acc, "interpolation": interp}],
                           "channels": [{"sampler": 0, "target": {"node": 1, "path": "weights"}}]})
    doc = {
        "asset": {"version": "2.0", "generator": "skinslide scripts/make_face_rig.py",
                  "copyright": "ICT FaceKit, USC Institute for Creative Technologies (MIT); "
                               "see its LICENSE.txt"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "ICT_root", "scale": [0.01, 0.01, 0.01], "children": [1]},
                  {"name": "face", "mesh": 0}],
        "meshes": [{"name": "ICT_head", "primitives": primitives,
                    "weights": [0.0] * len(EXPRESSIONS),
                    "extras": {"targetNames": EXPRESSIONS}}],
        "animations": animations,
        "buffers": [{"byteLength": len(buf.data)}],
        "bufferViews": buf.views,
        "accessors": buf.accessors,
    }
    face_triangles = sum(len(faces[i]) - 2 for i in groups[0])
    return doc, bytes(buf.data), sum(len(f) - 2 for f in head), face_triangles


def write(out, doc, data):
    while len(data) % 4:
        data += b"\0"
    doc["buffers"][0]["byteLength"] = len(data)
    if out.lower().endswith(".glb"):
        js = json.dumps(doc, separators=(",", ":")).encode()
        js += b" " * (-len(js) % 4)
        blob = struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(js) + 8 + len(data))
        blob += struct.pack("<I4s", len(js), b"JSON") + js
        blob += struct.pack("<I4s", len(data), b"BIN\0") + data
        with open(out, "wb") as f:
            f.write(blob)
        return
    bin_name = os.path.splitext(os.path.basename(out))[0] + ".bin"
    doc["buffers"][0]["uri"] = bin_name
    with open(os.path.join(os.path.dirname(os.path.abspath(out)), bin_name), "wb") as f:
        f.write(data)
    with open(out, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", help="the rig to write: .glb, or .gltf with a .bin beside it")
    ap.add_argument("--obj-dir", default=os.path.join(here, "..", "..", "shared", "data", "obj",
                                                      "ict-facekit"),
                    help="the ICT FaceKit OBJs (default ../shared/data/obj/ict-facekit)")
    ap.add_argument("--patch", help="also write the face region's patch file (triangles 0-18459)")
    a = ap.parse_args()
    doc, data, triangles, face_triangles = build(a.obj_dir)
    write(a.out, doc, bytearray(data))
    if a.patch:
        with open(a.patch, "w") as f:
            f.write("0-%d\n" % (face_triangles - 1))
    counts = [doc["accessors"][p["attributes"]["POSITION"]]["count"]
              for p in doc["meshes"][0]["primitives"]]
    print("make_face_rig: %s: %d triangles in 2 primitives (%s raw vertices), "
          "%d morph targets, clips %s; face region = triangles 0-%d"
          % (a.out, triangles, " + ".join(map(str, counts)), len(EXPRESSIONS),
             ", ".join('%d "%s"' % (i, c[0]) for i, c in enumerate(CLIPS)), face_triangles - 1))


if __name__ == "__main__":
    main()
