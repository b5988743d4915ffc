"""Blender's side of tests/cli/blender_cache.sh: a real client of skinslide's point caches. Run
inside Blender (Debian's 3.4.1), never by skinslide:

    blender -b --factory-startup -noaudio --python-exit-code 1 \\
        --python tests/cli/blender_cache.py -- COMMAND ARGS

    export OUT BIND.obj FRAME.obj...
        An animated mesh: BIND's vertices and faces (ids as in the OBJ), one shape key a FRAME,
        keyed to weight 1 at scene frame k (k = 1..N) and 0 at its neighbours. Writes it with
        Blender's own exporters, add-ons shipped with Blender: OUT/shot.pc2 (io_export_pc2:
        frames 1..N, sampling 1, object space, no Y-up rotation) and OUT/shot.mdd (io_shape_mdd:
        frames 1..N at 24 fps), and OUT/evaluated.f32: the positions Blender evaluated at each
        frame, N x V x 3 little-endian float32, for the test to check what skinslide reads.
    play BIND.obj N CACHE OBJ_DIR [CACHE OBJ_DIR ...]
        For each CACHE (.pc2 or .mdd): BIND's mesh with a Mesh Cache modifier playing it (time
        mode FRAME, frame_start 1: scene frame f shows sample f - 1; no interpolation, no axis
        change, factor 1). At every scene frame 1..N the evaluated positions must be skinslide's
        own slid positions, OBJ_DIR's N OBJ files in name order (doubles), rounded to float32,
        exactly. Prints "play CACHE: N frames, V vertices, max |blender - skinslide| E (F of a
        float32 ulp)" and exits 1 on any difference.
"""
import os
import sys

import addon_utils
import bpy
import numpy as np


def read_obj(path):
    """-> (V float64 (n,3), faces as lists of 0-based ids)."""
    verts, faces = [], []
    with open(path) as fh:
        for line in fh:
            p = line.split()
            if not p:
                continue
            if p[0] == "v":
                verts.append((float(p[1]), float(p[2]), float(p[3])))
            elif p[0] == "f":
                ids = [int(t.split("/")[0]) for t in p[1:]]
                faces.append([i - 1 if i > 0 else len(verts) + i for i in ids])
    return np.array(verts, np.float64).reshape(-1, 3), faces


def build_object(verts, faces, name="skin"):
    """A mesh object with exactly these vertices (float32) and faces, in this order."""
    me = bpy.data.meshes.new(name)
    me.from_pydata(verts.astype(np.float32).tolist(), [], faces)
    me.update()
    got = np.empty(3 * len(me.vertices), np.float32)
    me.vertices.foreach_get("co", got)
    if len(me.vertices) != len(verts) or not np.array_equal(got.reshape(-1, 3),
                                                             verts.astype(np.float32)):
        raise SystemExit("blender_cache.py: Blender changed the bind's vertices")
    ob = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(ob)
    bpy.context.view_layer.objects.active = ob
    ob.select_set(True)
    return ob


def evaluated(ob):
    depsgraph = bpy.context.evaluated_depsgraph_get()
    me = ob.evaluated_get(depsgraph).to_mesh()
    co = np.empty(3 * len(me.vertices), np.float32)
    me.vertices.foreach_get("co", co)
    ob.evaluated_get(depsgraph).to_mesh_clear()
    return co.reshape(-1, 3)


def export(out, bind, frames):
    verts, faces = read_obj(bind)
    ob = build_object(verts, faces)
    ob.shape_key_add(name="Basis")
    n = len(frames)
    for k, path in enumerate(frames, start=1):
        fv, _ = read_obj(path)
        key = ob.shape_key_add(name="frame_%04d" % k)
        key.data.foreach_set("co", fv.astype(np.float32).ravel())
        for frame, value in ((k - 1, 0.0), (k, 1.0), (k + 1, 0.0)):
            key.value = value
            key.keyframe_insert("value", frame=frame)
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, n
    for module in ("io_export_pc2", "io_shape_mdd"):
        if addon_utils.enable(module, default_set=True) is None:
            raise SystemExit("blender_cache.py: cannot enable the add-on " + module)
    os.makedirs(out, exist_ok=True)
    result = bpy.ops.export_shape.pc2(filepath=os.path.join(out, "shot.pc2"), rot_x90=False,
                                      world_space=False, apply_modifiers=True, range_start=1,
                                      range_end=n, sampling="1")
    if "FINISHED" not in result:
        raise SystemExit("blender_cache.py: the PC2 export failed: %s" % (result,))
    result = bpy.ops.export_shape.mdd(filepath=os.path.join(out, "shot.mdd"), fps=24,
                                      frame_start=1, frame_end=n, use_rest_frame=False)
    if "FINISHED" not in result:
        raise SystemExit("blender_cache.py: the MDD export failed: %s" % (result,))
    with open(os.path.join(out, "evaluated.f32"), "wb") as fh:
        for f in range(1, n + 1):
            scene.frame_set(f)
            fh.write(evaluated(ob).astype("<f4").tobytes())
    print("export: %d frames of %d vertices -> %s" % (n, len(verts), out))


def play(bind, n, pairs):
    verts, faces = read_obj(bind)
    ok = True
    for cache, obj_dir in pairs:
        ob = build_object(verts, faces, name=os.path.basename(cache))
        md = ob.modifiers.new("cache", "MESH_CACHE")
        md.cache_format = "PC2" if cache.lower().endswith(".pc2") else "MDD"
        md.filepath = cache
        md.time_mode, md.play_mode = "FRAME", "SCENE"
        md.frame_start, md.frame_scale = 1.0, 1.0
        md.interpolation = "NONE"
        md.forward_axis, md.up_axis = "POS_Y", "POS_Z"
        md.factor = 1.0
        expected = sorted(f for f in os.listdir(obj_dir) if f.endswith(".obj"))
        if len(expected) != n:
            raise SystemExit("blender_cache.py: %d OBJ files in %s, expected %d"
                             % (len(expected), obj_dir, n))
        worst = worst_ulps = 0.0
        for f in range(1, n + 1):
            bpy.context.scene.frame_set(f)
            got = evaluated(ob)
            own, _ = read_obj(os.path.join(obj_dir, expected[f - 1]))
            if got.shape != own.shape:
                raise SystemExit("blender_cache.py: the modifier did not play %s" % cache)
            error = np.abs(got.astype(np.float64) - own)
            ulp = np.spacing(np.abs(own).astype(np.float32)).astype(np.float64)
            worst = max(worst, float(error.max()))
            worst_ulps = max(worst_ulps, float((error / ulp).max()))
            if not np.array_equal(got, own.astype(np.float32)):
                bad = np.argwhere(got != own.astype(np.float32))[0]
                print("play %s: frame %d vertex %d: Blender %r, skinslide %r" % (
                    cache, f, bad[0], got[bad[0]].tolist(), own[bad[0]].tolist()))
                ok = False
        print("play %s: %d frames, %d vertices, max |blender - skinslide| %.3g (%.3g of a "
              "float32 ulp)" % (cache, n, len(verts), worst, worst_ulps))
        bpy.data.objects.remove(ob)
    if not ok:
        raise SystemExit(1)


def main(argv):
    if argv[:1] == ["export"] and len(argv) >= 4:
        export(argv[1], argv[2], argv[3:])
    elif argv[:1] == ["play"] and len(argv) >= 5 and len(argv) % 2 == 1:
        play(argv[1], int(argv[2]), list(zip(argv[3::2], argv[4::2])))
    else:
        raise SystemExit(__doc__)


main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
