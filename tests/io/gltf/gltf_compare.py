#!/usr/bin/env python3
"""Are two glTF files the same document? Used by the glTF round-trip tests.

    gltf_compare.py A B [--edited N,M,...]

Compares the JSON of A and B after removing properties equal to their glTF 2.0 schema default
(a writer may omit or spell them out), and the bytes of every buffer (GLB BIN chunk, .bin file
or data URI). Buffer URIs are compared only through their bytes. Accessors listed in --edited
may differ in min/max; their buffer bytes are compared by the caller. Exit 0 when equivalent,
1 with the differences listed otherwise.
"""
import base64
import json
import os
import struct
import sys
import urllib.parse

IDENTITY = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
# (collection path pattern, property, default); '*' matches any index or key.
DEFAULTS = [
    ("accessors/*", "byteOffset", 0), ("accessors/*", "normalized", False),
    ("accessors/*/sparse/indices", "byteOffset", 0), ("accessors/*/sparse/values", "byteOffset", 0),
    ("bufferViews/*", "byteOffset", 0),
    ("meshes/*/primitives/*", "mode", 4),
    ("animations/*/samplers/*", "interpolation", "LINEAR"),
    ("samplers/*", "wrapS", 10497), ("samplers/*", "wrapT", 10497),
    ("materials/*", "emissiveFactor", [0, 0, 0]), ("materials/*", "alphaMode", "OPAQUE"),
    ("materials/*", "alphaCutoff", 0.5), ("materials/*", "doubleSided", False),
    ("materials/*/pbrMetallicRoughness", "baseColorFactor", [1, 1, 1, 1]),
    ("materials/*/pbrMetallicRoughness", "metallicFactor", 1),
    ("materials/*/pbrMetallicRoughness", "roughnessFactor", 1),
    ("materials/*/pbrMetallicRoughness/baseColorTexture", "texCoord", 0),
    ("materials/*/pbrMetallicRoughness/metallicRoughnessTexture", "texCoord", 0),
    ("materials/*/normalTexture", "texCoord", 0), ("materials/*/normalTexture", "scale", 1),
    ("materials/*/occlusionTexture", "texCoord", 0), ("materials/*/occlusionTexture", "strength", 1),
    ("materials/*/emissiveTexture", "texCoord", 0),
    ("nodes/*", "matrix", IDENTITY), ("nodes/*", "rotation", [0, 0, 0, 1]),
    ("nodes/*", "scale", [1, 1, 1]), ("nodes/*", "translation", [0, 0, 0]),
]


def load(path):
    data = open(path, "rb").read()
    if data[:4] == b"glTF":
        n = struct.unpack("<I", data[12:16])[0]
        doc = json.loads(data[20:20 + n])
        off = 20 + n
        bin_chunk = b""
        if off + 8 <= len(data):
            m = struct.unpack("<I", data[off:off + 4])[0]
            bin_chunk = data[off + 8:off + 8 + m]
    else:
        doc, bin_chunk = json.loads(data), b""
    buffers = []
    for b in doc.get("buffers", []):
        uri = b.get("uri")
        if uri is None:
            raw = bin_chunk
        elif uri.startswith("data:"):
            raw = base64.b64decode(uri.split(",", 1)[1])
        else:
            raw = open(os.path.join(os.path.dirname(path), urllib.parse.unquote(uri)), "rb").read()
        buffers.append(raw[:b["byteLength"]])
        b.pop("uri", None)
    return doc, buffers


def matches(pattern, path):
    p, q = pattern.split("/"), path.split("/")
    return len(p) == len(q) and all(a == "*" or a == b for a, b in zip(p, q))


def strip_defaults(node, path=""):
    if isinstance(node, dict):
        for pattern, key, default in DEFAULTS:
            if key in node and matches(pattern, path) and node[key] == default:
                del node[key]
        for k, v in node.items():
            strip_defaults(v, f"{path}/{k}" if path else k)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            strip_defaults(v, f"{path}/{i}")


def diff(a, b, path, out):
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a:
                out.append(f"{path}/{k}: only in B")
            elif k not in b:
                out.append(f"{path}/{k}: only in A")
            else:
                diff(a[k], b[k], f"{path}/{k}", out)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{path}: {len(a)} items in A, {len(b)} in B")
        for i, (x, y) in enumerate(zip(a, b)):
            diff(x, y, f"{path}/{i}", out)
    elif a != b:
        out.append(f"{path}: {str(a)[:60]} != {str(b)[:60]}")


def main():
    args = sys.argv[1:]
    edited = set()
    if "--edited" in args:
        i = args.index("--edited")
        edited = {int(x) for x in args[i + 1].split(",") if x}
        del args[i:i + 2]
    (ja, ba), (jb, bb) = load(args[0]), load(args[1])
    for j in (ja, jb):
        strip_defaults(j)
        for i in edited:
            if i < len(j.get("accessors", [])):
                j["accessors"][i].pop("min", None)
                j["accessors"][i].pop("max", None)
    out = []
    diff(ja, jb, "", out)
    if not edited:
        if len(ba) != len(bb):
            out.append(f"buffers: {len(ba)} in A, {len(bb)} in B")
        for i, (x, y) in enumerate(zip(ba, bb)):
            if x != y:
                out.append(f"buffer {i}: bytes differ ({len(x)} vs {len(y)} bytes)")
    for line in out:
        print(line)
    return 1 if out else 0


if __name__ == "__main__":
    sys.exit(main())
