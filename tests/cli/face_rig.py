#!/usr/bin/python3
"""A facial rig of glTF morph targets as the frame source (--animation), end to end.

scripts/make_face_rig.py builds the rig from the shared ICT FaceKit OBJs (the neutral head, four
expressions as morph targets, clips "blend" LINEAR, "cubic" CUBICSPLINE, "step" STEP). skinslide
poses it with --strength 0 (nothing slides) and writes OBJ frames; each frame must be
neutral + sum_i w_i (expression_i - neutral), computed here in double from the OBJ files with the
weights of glTF 2.0 Appendix C (make_face_rig.weights_at), to 1e-5 of the head's bounding-box
diagonal: where one weight is 1 and the others 0, that expression OBJ. Output vertices are
matched to OBJ vertices through the faces (OBJ quad f is triangles 2f and 2f+1). Then the
default slide of a few frames runs and its GLB frames are checked static (no morph targets)
and, with the rig itself, passed through the Khronos validator when scripts/gltf_validate.sh
can run it (npm).

Usage: SKINSLIDE=path/to/skinslide tests/cli/face_rig.py
Exit 0 passed, 1 failed, 77 skipped (../shared missing; SKINSLIDE_REQUIRE_SHARED=1 fails instead).
"""
import importlib.util
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SHARED = os.environ.get("SKINSLIDE_SHARED_DIR") or os.path.join(os.path.dirname(ROOT), "shared")
OBJ_DIR = os.path.join(SHARED, "data", "obj", "ict-facekit")

spec = importlib.util.spec_from_file_location("make_face_rig",
                                              os.path.join(ROOT, "scripts", "make_face_rig.py"))
rig = importlib.util.module_from_spec(spec)
spec.loader.exec_module(rig)

failures = []
passed = 0


def check(name, ok, detail=""):
    global passed
    if ok:
        passed += 1
    else:
        failures.append(name)
        print("FAIL: %s%s" % (name, (": " + detail) if detail else ""), file=sys.stderr)


def read_v_f(path):
    v, f = [], []
    with open(path) as fh:
        for line in fh:
            if line.startswith("v "):
                v.append(tuple(float(x) for x in line.split()[1:4]))
            elif line.startswith("f "):
                f.append([int(c.split("/")[0]) - 1 for c in line.split()[1:]])
    return v, f


def read_glb(path):
    data = open(path, "rb").read()
    n = struct.unpack_from("<I", data, 12)[0]
    return json.loads(data[20:20 + n]), data[28 + n:28 + n + struct.unpack_from("<I", data, 20 + n)[0]]


def floats(doc, chunk, accessor):
    """A plain float VEC3 accessor's elements."""
    a = doc["accessors"][accessor]
    view = doc["bufferViews"][a["bufferView"]]
    base = view.get("byteOffset", 0) + a.get("byteOffset", 0)
    stride = view.get("byteStride", 12)
    return [struct.unpack_from("<3f", chunk, base + i * stride) for i in range(a["count"])]


def run(args, **kw):
    return subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, **kw)


def main():
    binary = os.environ.get("SKINSLIDE")
    if not binary:
        sys.exit("set SKINSLIDE to the skinslide binary")
    needed = [os.path.join(OBJ_DIR, n + ".obj") for n in ["generic_neutral_mesh"] + rig.EXPRESSIONS]
    for path in needed:
        if not os.path.exists(path):
            if os.environ.get("SKINSLIDE_REQUIRE_SHARED") == "1":
                print("FAIL: missing %s (SKINSLIDE_REQUIRE_SHARED=1)" % path, file=sys.stderr)
                return 1
            print("SKIP: missing %s" % path)
            return 77
    tmp = tempfile.mkdtemp(prefix="skinslide_face_rig.")
    try:
        return test(binary, tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def test(binary, tmp):
    glb, gltf, patch = (os.path.join(tmp, n) for n in ("face.glb", "face.gltf", "face.txt"))
    for out in (glb, gltf):
        r = run([sys.executable, os.path.join(ROOT, "scripts", "make_face_rig.py"), out,
                 "--obj-dir", OBJ_DIR, "--patch", patch])
        check("make_face_rig.py writes " + os.path.basename(out), r.returncode == 0, r.stdout)
    if failures:
        return 1
    check("the patch is the face region", open(patch).read() == "0-18459\n")

    neutral, faces = read_v_f(os.path.join(OBJ_DIR, "generic_neutral_mesh.obj"))
    expressions = [read_v_f(os.path.join(OBJ_DIR, n + ".obj"))[0] for n in rig.EXPRESSIONS]
    head_quads = 9230 + 4804
    lo = [min(neutral[v][i] for f in faces[:head_quads] for v in f) for i in range(3)]
    hi = [max(neutral[v][i] for f in faces[:head_quads] for v in f) for i in range(3)]
    diagonal = sum((h - l) ** 2 for l, h in zip(lo, hi)) ** 0.5

    def expected(weights):
        return [tuple(n[i] + sum(w * (e[v][i] - n[i]) for w, e in zip(weights, expressions)
                                 if w != 0) for i in range(3))
                for v, n in enumerate(neutral)]

    def compare(obj_path, weights, label):
        """Largest |frame - expected| / diagonal, the output vertices matched via the faces."""
        v, f = read_v_f(obj_path)
        if len(f) != 2 * head_quads:
            check(label + ": triangle count", False, "%d, expected %d" % (len(f), 2 * head_quads))
            return None
        want = expected(weights)
        to_obj = [-1] * len(v)
        worst = 0.0
        for q in range(head_quads):
            quad = faces[q]
            for k, tri in enumerate(((quad[0], quad[1], quad[2]), (quad[0], quad[2], quad[3]))):
                for out_id, obj_id in zip(f[2 * q + k], tri):
                    if to_obj[out_id] not in (-1, obj_id):
                        check(label + ": faces match the OBJ's", False, "vertex %d" % out_id)
                        return None
                    to_obj[out_id] = obj_id
        for out_id, obj_id in enumerate(to_obj):
            d = max(abs(a - b) for a, b in zip(v[out_id], want[obj_id]))
            worst = max(worst, d)
        return worst / diagonal

    def frames(clip, extra, outdir):
        r = run([binary, "-q", "--patch", patch, "--animation", clip, "--format", "obj",
                 "--strength", "0", glb, "-o", outdir] + extra)
        check("--animation %s %s runs" % (clip, " ".join(extra)), r.returncode == 0, r.stdout)
        return sorted(os.listdir(outdir)) if r.returncode == 0 else []

    clips = {c[0]: c for c in rig.CLIPS}
    report = []
    # "blend" at its key times (--keyframes): 0.5, 1.5, 2.5, 3.5 s are the four expressions.
    names = frames("blend", [], os.path.join(tmp, "blend"))
    times = clips["blend"][2]
    check("blend: one frame per key time", len(names) == len(times), str(names))
    for k, name in enumerate(names[:len(times)]):
        w = rig.weights_at(clips["blend"], times[k])
        err = compare(os.path.join(tmp, "blend", name), w, "blend " + name)
        if err is None:
            continue
        one = [i for i, x in enumerate(w) if x == 1]
        label = "blend %s (t = %g s, %s)" % (
            name, times[k], rig.EXPRESSIONS[one[0]] if one and sum(w) == 1 else "weights %s" % w)
        report.append("%s: %.2e" % (label, err))
        check(label + " matches to 1e-5 of the diagonal", err < 1e-5, "%.3g" % err)
    check("blend: each expression is a frame", all(
        rig.weights_at(clips["blend"], t) == [1.0 if i == j else 0.0 for i in range(4)]
        for j, t in enumerate([0.5, 1.5, 2.5, 3.5])))
    # "cubic" every 0.25 s (between keys: the Hermite spline), "step" every 0.25 s (held keys).
    for clip, fps in (("cubic", "4"), ("step", "4")):
        names = frames(clip, ["--fps", fps], os.path.join(tmp, clip))
        times = [k / float(fps) for k in range(len(names))]
        check("%s --fps %s: frames to the clip's end" % (clip, fps),
              len(names) == int(clips[clip][2][-1] * float(fps)) + 1, str(names))
        for name, t in zip(names, times):
            err = compare(os.path.join(tmp, clip, name), rig.weights_at(clips[clip], t),
                          "%s %s" % (clip, name))
            if err is not None:
                report.append("%s %s (t = %g s): %.2e" % (clip, name, t, err))
                check("%s %s matches to 1e-5 of the diagonal" % (clip, name), err < 1e-5,
                      "%.3g" % err)

    # NORMAL: the morphed normals, renormalised. Frame 1 of "blend" is jawOpen: each raw
    # vertex's normal is jawOpen's area-weighted normal (make_face_rig.vertex_normals).
    posed = os.path.join(tmp, "posed")
    r = run([binary, "-q", "--patch", patch, "--animation", "blend", "--frames", "1",
             "--strength", "0", glb, "-o", posed])
    check("blend frame 1 as GLB runs", r.returncode == 0, r.stdout)
    if r.returncode == 0:
        pos, _, obj_faces, materials = rig.read_obj(os.path.join(OBJ_DIR, "generic_neutral_mesh.obj"))
        groups = rig.head_groups(obj_faces, materials)
        jaw = rig.vertex_normals(expressions[0], [obj_faces[i] for g in groups for i in g])
        doc, chunk = read_glb(os.path.join(posed, "face.0001.glb"))
        worst = 0.0
        for g, prim in zip(groups, doc["meshes"][0]["primitives"]):
            raw, _ = rig.primitive_vertices(obj_faces, g)
            normals = floats(doc, chunk, prim["attributes"]["NORMAL"])
            for (v, _), n in zip(raw, normals):
                worst = max(worst, max(abs(a - b) for a, b in zip(n, jaw[v])))
        report.append("blend face.0001.glb NORMAL vs jawOpen's normals: %.2e" % worst)
        check("jawOpen's frame has jawOpen's normals (to 1e-5)", worst < 1e-5, "%.3g" % worst)

    # The default slide on two frames: static GLB copies that validate.
    slid = os.path.join(tmp, "slid")
    r = run([binary, "-q", "--patch", patch, "--animation", "blend", "--frames", "1,2", glb,
             "-o", slid])
    check("the default slide of blend frames 1 and 2 runs", r.returncode == 0, r.stdout)
    outputs = sorted(os.path.join(slid, n) for n in os.listdir(slid)) if r.returncode == 0 else []
    check("two GLB frames", [os.path.basename(p) for p in outputs] ==
          ["face.0001.glb", "face.0002.glb"], str(outputs))
    for path in outputs:
        mesh = read_glb(path)[0]["meshes"][0]
        check(os.path.basename(path) + " is static: no morph targets, weights or weights channels",
              all("targets" not in p for p in mesh["primitives"]) and "weights" not in mesh and
              all(c["target"]["path"] != "weights" for a in doc.get("animations", [])
                  for c in a["channels"]))
    r = run(["bash", os.path.join(ROOT, "scripts", "gltf_validate.sh"), glb, gltf] + outputs)
    if r.returncode == 2:
        print("NOTE: the Khronos glTF validator is unavailable (node/npm): not run\n" + r.stdout)
    else:
        check("the rig and the slid frames pass the Khronos validator", r.returncode == 0,
              r.stdout)
        print(r.stdout, end="")

    print("\n".join("  " + line for line in report))
    print("face_rig: %d passed, %d failed" % (passed, len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
