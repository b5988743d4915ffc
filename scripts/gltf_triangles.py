#!/usr/bin/env python3
"""Lists the triangles of a glTF/GLB mesh as skinslide numbers them, to help write patch files.

    scripts/gltf_triangles.py FILE [--mesh INDEX] [--axis x|y|z]

One line per triangle: its index (the face index of patch files: triangles of the mesh's
TRIANGLES primitives in primitive order), its primitive, and the lowest and highest coordinate
of its corners along --axis (default z). Then the runs of consecutive triangles that share the
same (low, high) span, which on limbs and cylinders are rings. A helper with the common case
only: float POSITION without sparse substitution, TRIANGLES mode; skinslide itself reads more.
"""
import argparse
import base64
import json
import os
import struct
import sys


def load(path):
    data = open(path, "rb").read()
    if data[:4] == b"glTF":
        n = struct.unpack("<I", data[12:16])[0]
        doc = json.loads(data[20:20 + n])
        off = 20 + n
        chunk = data[off + 8:off + 8 + struct.unpack("<I", data[off:off + 4])[0]] if off < len(data) else b""
    else:
        doc, chunk = json.loads(data), b""
    buffers = []
    for b in doc.get("buffers", []):
        uri = b.get("uri")
        if uri is None:
            buffers.append(chunk)
        elif uri.startswith("data:"):
            buffers.append(base64.b64decode(uri.split(",", 1)[1]))
        else:
            buffers.append(open(os.path.join(os.path.dirname(path), uri), "rb").read())
    return doc, buffers


def read(doc, buffers, index):
    a = doc["accessors"][index]
    v = doc["bufferViews"][a["bufferView"]]
    width = {"SCALAR": 1, "VEC3": 3}[a["type"]]
    fmt = {5121: "B", 5123: "H", 5125: "I", 5126: "f"}[a["componentType"]]
    size = struct.calcsize(fmt) * width
    stride = v.get("byteStride", size)
    base = v.get("byteOffset", 0) + a.get("byteOffset", 0)
    data = buffers[v["buffer"]]
    return [struct.unpack_from("<" + fmt * width, data, base + i * stride) for i in range(a["count"])]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("file")
    ap.add_argument("--mesh", type=int, default=0)
    ap.add_argument("--axis", choices="xyz", default="z")
    args = ap.parse_args()
    axis = "xyz".index(args.axis)
    doc, buffers = load(args.file)
    rows = []
    for p, prim in enumerate(doc["meshes"][args.mesh]["primitives"]):
        if prim.get("mode", 4) != 4:
            continue
        pos = read(doc, buffers, prim["attributes"]["POSITION"])
        ids = [i[0] for i in read(doc, buffers, prim["indices"])] if "indices" in prim else list(range(len(pos)))
        for t in range(0, len(ids) - 2, 3):
            c = [pos[ids[t + k]][axis] for k in range(3)]
            rows.append((len(rows), p, round(min(c), 4), round(max(c), 4)))
    for r in rows:
        print(f"{r[0]}\tprimitive {r[1]}\t{args.axis} {r[2]} .. {r[3]}")
    print("# runs of triangles with the same span:")
    start = 0
    for i in range(1, len(rows) + 1):
        if i == len(rows) or rows[i][2:] != rows[start][2:]:
            first, last = rows[start][0], rows[i - 1][0]
            print(f"# {first}-{last}\t{args.axis} {rows[start][2]} .. {rows[start][3]}")
            start = i


if __name__ == "__main__":
    sys.exit(main())
