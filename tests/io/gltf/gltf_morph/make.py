#!/usr/bin/python3
"""Writes the small glTF files of tests/io/gltf/gltf_morph_test.cpp (JSON with a base64 data-URI
buffer): every number is listed below, the expected poses are worked out by hand in the test.
Run it from anywhere; it rewrites the .gltf files beside itself. Standard library only.

morph_quads.gltf   unskinned mesh, 2 morph targets, 3 primitives (AnimatedMorphCube-style)
  node 0 "root"  translation (0,0,10), children [1]
  node 1 "face"  mesh 0, translation (5,0,0), rotation 90 deg about z, weights [0.25, 0.75]
  node 2 "twin"  mesh 0 as well (its weights channel must not move node 1's instance)
  mesh 0 weights [0.5, 0] (overridden by node 1's)
    primitive 0  TRIANGLES, indexed 0 1 2  0 2 3; POSITION (0,0,0) (1,0,0) (1,1,0) (0,1,0);
                 NORMAL (0,0,1) x4
       target 0  POSITION sparse without bufferView: vertices 1, 2 += (0,0,1);
                 NORMAL (-1,0,0) x4
       target 1  POSITION (0,0,0) (0,0,0) (0,1,0) (0,1,0); no NORMAL
    primitive 1  TRIANGLES, not indexed; POSITION sparse over a bufferView:
                 (2,0,0) (3,0,0) (2,1,0) with element 2 replaced by (2,1,0.5); NORMAL (0,0,1) x3
       target 0  POSITION sparse over a bufferView: (0,0,1) x3 with element 0 replaced by (0,0,2)
       target 1  NORMAL (0,1,0) x3 only (no POSITION)
    primitive 2  POINTS over primitive 1's accessors (not part of the surface)
  animation 0 "step"   node 1 weights, STEP, t = 0 1 2: (0,0) (1,0) (0,1)
  animation 1 "cubic"  node 2 weights LINEAR t = 0 3 (ignored); node 1 weights CUBICSPLINE
                       t = 0 2: (in, value, out) = ((0,0), (0,0), (1,0)) and ((0,-1), (1,1),
                       (0,0)); node 0 translation STEP t = 0 1.5: (0,0,10) (0,0,20)
  animation 2 "move"   node 1 translation LINEAR t = 0 1: (5,0,0) (7,0,0)

skinned_morph.gltf  skinned mesh with 1 morph target (morph first, then skin)
  node 0 "hip" joint 0, children [1]; node 1 "knee" joint 1, translation (0,1,0);
  node 2 mesh 0 skin 0
  inverse bind matrices: identity, translation (0,-1,0)
  primitive 0  TRIANGLES 0 1 2  0 2 3; POSITION (0,0,0) (1,0,0) (1,2,0) (0,2,0); NORMAL (0,0,1) x4
               joints/weights: v0 v1 hip; v2 knee; v3 hip 0.5 + knee 0.5
     target 0  POSITION v2 += (1,0,0), v3 += (0,0,1); NORMAL v2 += (1,0,0)
  animation 0 "bend"  knee rotation LINEAR t = 0 1: identity, 90 deg about z;
                      node 2 weights STEP t = 0 0.5: (0) (1)

static_triangle.gltf  neither skinned nor morphed
  node 0 "parent" children [1]; node 1 "triangle" mesh 0; node 2 "elsewhere"
  primitive 0  POSITION (0,0,0) (1,0,0) (0,1,0)
  animation 0 "slide"  node 2 translation LINEAR t = 0 1: (0,0,0) (1,0,0)
"""
import base64
import json
import math
import os
import struct

FLOAT, UBYTE, USHORT = 5126, 5121, 5123
TYPES = {1: "SCALAR", 3: "VEC3", 4: "VEC4", 16: "MAT4"}


class Gltf:
    def __init__(self):
        self.buf = bytearray()
        self.views = []
        self.accessors = []

    def view(self, data, target=None):
        while len(self.buf) % 4:
            self.buf.append(0)
        v = {"buffer": 0, "byteOffset": len(self.buf), "byteLength": len(data)}
        if target:
            v["target"] = target
        self.buf += data
        self.views.append(v)
        return len(self.views) - 1

    def floats(self, rows, target=None, bounds=False, sparse=None, no_view=False, count=None):
        """rows: list of tuples (VEC3 ...) or numbers (SCALAR). sparse: (indices, rows)."""
        rows = [r if isinstance(r, (tuple, list)) else (r,) for r in rows]
        n = len(rows[0]) if rows else len(sparse[1][0])
        a = {"componentType": FLOAT, "count": count if count is not None else len(rows),
             "type": TYPES[n]}
        if not no_view:
            a["bufferView"] = self.view(b"".join(struct.pack("<%df" % n, *r) for r in rows), target)
        full = [list(r) for r in rows] if not no_view else [[0.0] * n for _ in range(a["count"])]
        if sparse:
            idx, vals = sparse
            a["sparse"] = {
                "count": len(idx),
                "indices": {"bufferView": self.view(bytes(idx)), "componentType": UBYTE},
                "values": {"bufferView": self.view(
                    b"".join(struct.pack("<%df" % n, *r) for r in vals))}}
            for i, r in zip(idx, vals):
                full[i] = list(r)
        if bounds:
            a["min"] = [min(r[c] for r in full) for c in range(n)]
            a["max"] = [max(r[c] for r in full) for c in range(n)]
        self.accessors.append(a)
        return len(self.accessors) - 1

    def ushorts(self, values, n=1, target=None):
        a = {"bufferView": self.view(struct.pack("<%dH" % len(values), *values), target),
             "componentType": USHORT, "count": len(values) // n, "type": TYPES[n]}
        self.accessors.append(a)
        return len(self.accessors) - 1

    def ubytes4(self, values, target=34962):
        a = {"bufferView": self.view(bytes(values), target), "componentType": UBYTE,
             "count": len(values) // 4, "type": "VEC4"}
        self.accessors.append(a)
        return len(self.accessors) - 1

    def times(self, t):
        return self.floats(t, bounds=True)

    def document(self, rest):
        doc = {"asset": {"version": "2.0", "generator": "skinslide tests/io/gltf/gltf_morph/make.py"}}
        doc.update(rest)
        doc["buffers"] = [{"byteLength": len(self.buf), "uri": "data:application/octet-stream;base64,"
                           + base64.b64encode(bytes(self.buf)).decode()}]
        doc["bufferViews"] = self.views
        doc["accessors"] = self.accessors
        return doc


def write(name, doc):
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), name)
    with open(path, "w") as f:
        f.write(json.dumps(doc, indent=1) + "\n")


H = math.sqrt(0.5)
ARRAY = 34962


def morph_quads():
    g = Gltf()
    p0 = g.floats([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], ARRAY, bounds=True)
    n0 = g.floats([(0, 0, 1)] * 4, ARRAY)
    i0 = g.ushorts([0, 1, 2, 0, 2, 3], target=34963)
    p0t0 = g.floats([], bounds=True, no_view=True, count=4,
                    sparse=([1, 2], [(0, 0, 1), (0, 0, 1)]))
    n0t0 = g.floats([(-1, 0, 0)] * 4, ARRAY)
    p0t1 = g.floats([(0, 0, 0), (0, 0, 0), (0, 1, 0), (0, 1, 0)], ARRAY, bounds=True)
    p1 = g.floats([(2, 0, 0), (3, 0, 0), (2, 1, 0)], ARRAY, bounds=True,
                  sparse=([2], [(2, 1, 0.5)]))
    n1 = g.floats([(0, 0, 1)] * 3, ARRAY)
    p1t0 = g.floats([(0, 0, 1)] * 3, ARRAY, bounds=True, sparse=([0], [(0, 0, 2)]))
    n1t1 = g.floats([(0, 1, 0)] * 3, ARRAY)
    t012 = g.times([0, 1, 2])
    step_w = g.floats([0, 0, 1, 0, 0, 1])
    t03 = g.times([0, 3])
    twin_w = g.floats([0, 0, 1, 1])
    t02 = g.times([0, 2])
    cubic_w = g.floats([0, 0, 0, 0, 1, 0,  # key 0: in-tangent, value, out-tangent
                        0, -1, 1, 1, 0, 0])  # key 1
    t0_15 = g.times([0, 1.5])
    root_t = g.floats([(0, 0, 10), (0, 0, 20)])
    t01 = g.times([0, 1])
    move_t = g.floats([(5, 0, 0), (7, 0, 0)])
    targets0 = [{"POSITION": p0t0, "NORMAL": n0t0}, {"POSITION": p0t1}]
    targets1 = [{"POSITION": p1t0}, {"NORMAL": n1t1}]
    doc = g.document({
        "scene": 0, "scenes": [{"nodes": [0, 2]}],
        "nodes": [
            {"name": "root", "translation": [0, 0, 10], "children": [1]},
            {"name": "face", "mesh": 0, "translation": [5, 0, 0], "rotation": [0, 0, H, H],
             "weights": [0.25, 0.75]},
            {"name": "twin", "mesh": 0}],
        "meshes": [{"name": "quads", "weights": [0.5, 0], "primitives": [
            {"attributes": {"POSITION": p0, "NORMAL": n0}, "indices": i0, "targets": targets0},
            {"attributes": {"POSITION": p1, "NORMAL": n1}, "targets": targets1},
            {"attributes": {"POSITION": p1, "NORMAL": n1}, "mode": 0, "targets": targets1}]}],
        "animations": [
            {"name": "step",
             "samplers": [{"input": t012, "output": step_w, "interpolation": "STEP"}],
             "channels": [{"sampler": 0, "target": {"node": 1, "path": "weights"}}]},
            {"name": "cubic",
             "samplers": [{"input": t03, "output": twin_w},
                          {"input": t02, "output": cubic_w, "interpolation": "CUBICSPLINE"},
                          {"input": t0_15, "output": root_t, "interpolation": "STEP"}],
             "channels": [{"sampler": 0, "target": {"node": 2, "path": "weights"}},
                          {"sampler": 1, "target": {"node": 1, "path": "weights"}},
                          {"sampler": 2, "target": {"node": 0, "path": "translation"}}]},
            {"name": "move",
             "samplers": [{"input": t01, "output": move_t}],
             "channels": [{"sampler": 0, "target": {"node": 1, "path": "translation"}}]}]})
    write("morph_quads.gltf", doc)


def skinned_morph():
    g = Gltf()
    p = g.floats([(0, 0, 0), (1, 0, 0), (1, 2, 0), (0, 2, 0)], ARRAY, bounds=True)
    n = g.floats([(0, 0, 1)] * 4, ARRAY)
    j = g.ubytes4([0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0])
    w = g.floats([(1, 0, 0, 0), (1, 0, 0, 0), (1, 0, 0, 0), (0.5, 0.5, 0, 0)], ARRAY)
    i = g.ushorts([0, 1, 2, 0, 2, 3], target=34963)
    pt = g.floats([(0, 0, 0), (0, 0, 0), (1, 0, 0), (0, 0, 1)], ARRAY, bounds=True)
    nt = g.floats([(0, 0, 0), (0, 0, 0), (1, 0, 0), (0, 0, 0)], ARRAY)
    ibm = g.floats([(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1),
                    (1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1)])
    t01 = g.times([0, 1])
    rot = g.floats([(0, 0, 0, 1), (0, 0, H, H)])
    t005 = g.times([0, 0.5])
    wts = g.floats([0, 1])
    doc = g.document({
        "scene": 0, "scenes": [{"nodes": [0, 2]}],
        "nodes": [{"name": "hip", "children": [1]},
                  {"name": "knee", "translation": [0, 1, 0]},
                  {"name": "leg", "mesh": 0, "skin": 0}],
        "skins": [{"joints": [0, 1], "inverseBindMatrices": ibm}],
        "meshes": [{"name": "leg", "primitives": [
            {"attributes": {"POSITION": p, "NORMAL": n, "JOINTS_0": j, "WEIGHTS_0": w},
             "indices": i, "targets": [{"POSITION": pt, "NORMAL": nt}]}]}],
        "animations": [{"name": "bend",
                        "samplers": [{"input": t01, "output": rot},
                                     {"input": t005, "output": wts, "interpolation": "STEP"}],
                        "channels": [{"sampler": 0, "target": {"node": 1, "path": "rotation"}},
                                     {"sampler": 1, "target": {"node": 2, "path": "weights"}}]}]})
    write("skinned_morph.gltf", doc)


def static_triangle():
    g = Gltf()
    p = g.floats([(0, 0, 0), (1, 0, 0), (0, 1, 0)], ARRAY, bounds=True)
    t01 = g.times([0, 1])
    tr = g.floats([(0, 0, 0), (1, 0, 0)])
    doc = g.document({
        "scene": 0, "scenes": [{"nodes": [0, 2]}],
        "nodes": [{"name": "parent", "children": [1]}, {"name": "triangle", "mesh": 0},
                  {"name": "elsewhere"}],
        "meshes": [{"name": "triangle", "primitives": [{"attributes": {"POSITION": p}}]}],
        "animations": [{"name": "slide", "samplers": [{"input": t01, "output": tr}],
                        "channels": [{"sampler": 0,
                                      "target": {"node": 2, "path": "translation"}}]}]})
    write("static_triangle.gltf", doc)


morph_quads()
skinned_morph()
static_triangle()
