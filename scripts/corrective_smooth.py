"""Blender's Corrective Smooth modifier (the open-source delta mush) on skinslide's inputs: the
peer that scripts/quality.sh (method corrective-smooth) and scripts/bench.sh --peers measure.
A benchmark tool only, run inside Blender (Debian's blender 3.4.1); skinslide never uses it.

    blender -b --factory-startup -noaudio --python-exit-code 1 [-t 1] \\
        --python scripts/corrective_smooth.py -- COMMAND ARGS

    slide --bind B.obj --patch P.txt -o OUTDIR [--iterations 10] [--group free] FRAME.obj...
        For every frame (one Blender process for all): the frame's OBJ positions go into the
        mesh; Corrective Smooth with the bind as its rest smooths the patch; the evaluated
        positions are written as OUTDIR/<frame's file name> (`v` and `f` lines; same vertex
        count and order, the frame's faces). --group patch|mesh: the vertex group holds every
        vertex of the patch (its border moves too) or of the mesh (no restriction), for
        comparisons; the default, free, is the benchmark's.
    time --bind B.obj --patch P.txt --frame F.obj [--iterations 10] [--repeats 9] [--group free]
        Times the modifier's evaluation warm, as in playback (see `time_cs`), and prints
        "key value" lines (CPU milliseconds of the process; run with -t 1 for one thread).

Set-up (both commands):
  - mesh: built directly from the OBJ `v` and `f` lines (foreach_set on vertices, loops and
    polygons), so vertex ids are the OBJ's; no importer, no split, merge or triangulation.
    Blender stores float32 positions.
  - rest: rest_source 'BIND', bound (object.correctivesmooth_bind) while the mesh is at the bind,
    so the rest is the bind's positions; then the frame drives the mesh (slide: the frame's
    positions written into the mesh; time: a shape key holding the frame, animated).
  - vertex group "patch": the patch's free vertices (vertices of the patch's faces that are not on
    its boundary, i.e. not on an edge used by only one patch face: the vertices skinslide moves),
    weight 1. The modifier moves only them; every other vertex keeps the frame's position.
  - modifier: factor 0.5, smooth_type 'SIMPLE', scale 1 (Blender's defaults), iterations 10
    (Blender's default is 5), use_only_smooth False, use_pin_boundary True.
In the written frames, vertices outside the group are copied from the frame's text (they are
checked unmoved in float32 first), so the border and outside stay exactly the frame's.
Patch files: face ids (0-based) and ranges "a-b", whitespace separated, '#' comments.
"""
import os
import statistics
import sys
import time

import bpy
import numpy as np


def read_obj(path):
    """-> (V float64 (n,3), v_text list of 'x y z' strings, faces list of lists, 0-based)."""
    V, text, faces = [], [], []
    with open(path) as fh:
        for line in fh:
            p = line.split()
            if not p:
                continue
            if p[0] == "v":
                V.append((float(p[1]), float(p[2]), float(p[3])))
                text.append(" ".join(p[1:4]))
            elif p[0] == "f":
                f = []
                for t in p[1:]:
                    i = int(t.split("/")[0])
                    f.append(i - 1 if i > 0 else len(V) + i)
                faces.append(f)
    return np.array(V, np.float64).reshape(-1, 3), text, faces


def read_patch(path, nfaces):
    ids = []
    with open(path) as fh:
        for line in fh:
            for tok in line.split("#")[0].replace(",", " ").split():
                if "-" in tok[1:]:
                    a, b = tok.split("-", 1)
                    ids.extend(range(int(a), int(b) + 1))
                else:
                    ids.append(int(tok))
    ids = np.unique(np.array(ids, np.int64))
    if len(ids) == 0 or ids[0] < 0 or ids[-1] >= nfaces:
        raise SystemExit("corrective_smooth.py: bad patch %s (%d faces)" % (path, nfaces))
    return ids


def free_vertices(faces, patch, group="free"):
    """Vertices of the patch faces minus those on an edge used by one patch face only.
    group "patch": every vertex of the patch faces; "mesh": every vertex of the mesh."""
    a, b = [], []
    for i in patch:
        f = faces[i]
        a.extend(f)
        b.extend(f[1:] + f[:1])
    a = np.array(a, np.int64)
    b = np.array(b, np.int64)
    e = np.stack([np.minimum(a, b), np.maximum(a, b)], 1)
    eu, cnt = np.unique(e, axis=0, return_counts=True)
    border = np.unique(eu[cnt == 1])
    if group == "patch":
        return np.unique(a)
    if group == "mesh":
        return np.unique(np.fromiter((v for f in faces for v in f), np.int64))
    return np.setdiff1d(np.unique(a), border)


def build_object(V, faces, name="skin"):
    me = bpy.data.meshes.new(name)
    me.vertices.add(len(V))
    me.vertices.foreach_set("co", V.astype(np.float32).ravel())
    counts = np.array([len(f) for f in faces], np.int32)
    starts = np.zeros(len(faces), np.int32)
    np.cumsum(counts[:-1], out=starts[1:])
    loops = np.fromiter((v for f in faces for v in f), np.int32, int(counts.sum()))
    me.loops.add(len(loops))
    me.loops.foreach_set("vertex_index", loops)
    me.polygons.add(len(faces))
    me.polygons.foreach_set("loop_start", starts)
    me.polygons.foreach_set("loop_total", counts)
    me.update(calc_edges=True)
    changed = me.validate(verbose=False, clean_customdata=False)
    if len(me.vertices) != len(V) or len(me.polygons) != len(faces):
        raise SystemExit("corrective_smooth.py: Blender changed the mesh: %d/%d vertices, %d/%d faces"
                         % (len(me.vertices), len(V), len(me.polygons), len(faces)))
    got = np.empty(3 * len(V), np.float32)
    me.vertices.foreach_get("co", got)
    if not np.array_equal(got.reshape(-1, 3), V.astype(np.float32)):
        raise SystemExit("corrective_smooth.py: vertex order changed in Blender")
    ob = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(ob)
    bpy.context.view_layer.objects.active = ob
    ob.select_set(True)
    return ob, changed


def add_modifier(ob, free, iterations):
    vg = ob.vertex_groups.new(name="patch")
    vg.add(free.tolist(), 1.0, "REPLACE")
    md = ob.modifiers.new("cs", "CORRECTIVE_SMOOTH")
    md.factor = 0.5
    md.iterations = iterations
    md.scale = 1.0
    md.smooth_type = "SIMPLE"
    md.use_only_smooth = False
    md.use_pin_boundary = True
    md.vertex_group = "patch"
    md.rest_source = "BIND"
    # Bind: the modifier's input now is the bind's positions (mesh built from the bind).
    res = bpy.ops.object.correctivesmooth_bind(modifier=md.name)
    if "FINISHED" not in res or not md.is_bind:
        raise SystemExit("corrective_smooth.py: correctivesmooth_bind failed: %s" % (res,))
    print("corrective_smooth.py: bound (a \"Bind data required\" error above is the scene's "
          "evaluation before the bind, expected)")
    return md


def evaluated_positions(ob):
    dg = bpy.context.evaluated_depsgraph_get()
    ev = ob.evaluated_get(dg)
    me = ev.to_mesh()
    out = np.empty(3 * len(me.vertices), np.float32)
    me.vertices.foreach_get("co", out)
    ev.to_mesh_clear()
    return out.reshape(-1, 3)


def setup(args_bind, args_patch, iterations, group="free"):
    Vb, _, faces = read_obj(args_bind)
    patch = read_patch(args_patch, len(faces))
    free = free_vertices(faces, patch, group)
    ob, changed = build_object(Vb, faces)
    md = add_modifier(ob, free, iterations)
    info = ("%d vertices, %d faces, %d patch faces, vertex group: %d %s vertices%s"
            % (len(Vb), len(faces), len(patch), len(free),
               {"free": "free", "patch": "patch", "mesh": "mesh"}[group],
               "; validate() reported changes" if changed else ""))
    return Vb, faces, free, ob, md, info


def cmd_slide(opts):
    Vb, faces, free, ob, md, info = setup(opts["--bind"], opts["--patch"], opts["--iterations"],
                                          opts["--group"])
    out_dir = opts["-o"]
    os.makedirs(out_dir, exist_ok=True)
    # The rest must be the bind: evaluated at the bind, the modifier must return the bind.
    at_bind = evaluated_positions(ob)
    rest_err = float(np.abs(at_bind - Vb.astype(np.float32)).max())
    ingroup = np.zeros(len(Vb), bool)
    ingroup[free] = True
    me = ob.data
    worst_moved = 0.0
    worst_outside = 0.0
    for path in opts["frames"]:
        Vf, text, ff = read_obj(path)
        if len(Vf) != len(Vb) or ff != faces:
            raise SystemExit("corrective_smooth.py: %s: topology differs from the bind's" % path)
        F32 = Vf.astype(np.float32)
        me.vertices.foreach_set("co", F32.ravel())
        me.update()
        S = evaluated_positions(ob)
        outside = float(np.abs(S[~ingroup] - F32[~ingroup]).max()) if (~ingroup).any() else 0.0
        if outside != 0.0:
            raise SystemExit("corrective_smooth.py: %s: vertices outside the group moved by %g"
                             % (path, outside))
        if not np.all(np.isfinite(S)):
            raise SystemExit("corrective_smooth.py: %s: non-finite output" % path)
        worst_moved = max(worst_moved, float(np.linalg.norm(S[ingroup] - F32[ingroup], axis=1).max()))
        lines = []
        for i in range(len(Vf)):
            if ingroup[i]:
                x, y, z = S[i]
                lines.append("v %.9g %.9g %.9g\n" % (x, y, z))
            else:
                lines.append("v " + text[i] + "\n")
        for f in faces:
            lines.append("f " + " ".join(str(v + 1) for v in f) + "\n")
        with open(os.path.join(out_dir, os.path.basename(path)), "w") as fh:
            fh.write("# Blender %s Corrective Smooth, %d iterations (scripts/corrective_smooth.py)\n"
                     % (bpy.app.version_string, md.iterations))
            fh.writelines(lines)
        worst_outside = max(worst_outside, outside)
    print("corrective_smooth: %s; %d frames; at the bind the output differs from the bind by %g "
          "(float32); largest move %g; outside the group unmoved" % (info, len(opts["frames"]),
                                                                    rest_err, worst_moved))


def time_cs(ob, md, Vf, repeats):
    """Warm evaluation, as in playback: the frame is a shape key whose value is animated
    (constant keyframes alternating 1 and 0.9999), and scene.frame_set(t) evaluates the scene.
    An animated value reaches the object through the depsgraph's relations, so the evaluated
    modifier keeps its rest cache (delta_cache) between frames; a tag from Python
    (update_tag, mesh.update, an RNA property set) re-copies the evaluated object and drops the
    cache, so every evaluation would pay the rest's smoothing again (measured: twice the time).
    Rest 'BIND', not 'ORCO': with ORCO an animated shape key tags the mesh, which also drops it.
    Timed: frame_set with the modifier on, then the same with it off (shape key mix, mesh copy:
    the overhead); modifier alone = the difference of the medians."""
    sc = bpy.context.scene
    basis = ob.shape_key_add(name="Basis", from_mix=False)
    key = ob.shape_key_add(name="frame", from_mix=False)
    key.data.foreach_set("co", Vf.astype(np.float32).ravel())
    n = repeats + 2
    for t in range(1, n + 1):
        key.value = 1.0 if t % 2 else 0.9999
        key.keyframe_insert("value", frame=t)
    for kp in ob.data.shape_keys.animation_data.action.fcurves[0].keyframe_points:
        kp.interpolation = "CONSTANT"
    del basis

    def run():
        cpu, wall = [], []
        for t in range(2, n + 1):
            w0, c0 = time.perf_counter(), time.process_time()
            sc.frame_set(t)
            cpu.append(time.process_time() - c0)
            wall.append(time.perf_counter() - w0)
        return statistics.median(cpu) * 1e3, statistics.median(wall) * 1e3

    c0 = time.process_time()
    sc.frame_set(1)  # first evaluation: the rest's deltas computed (cold)
    cold = (time.process_time() - c0) * 1e3
    on_cpu, on_wall = run()
    sc.frame_set(1)
    md.show_viewport = False
    sc.frame_set(1)
    off_cpu, off_wall = run()
    md.show_viewport = True
    sc.frame_set(1)
    md.use_only_smooth = True  # the smoothing pass alone (a cold/warm check)
    sc.frame_set(1)
    smooth_cpu, _ = run()
    md.use_only_smooth = False
    return {"cs_cold_ms": cold, "cs_frame_ms": on_cpu, "cs_frame_wall_ms": on_wall,
            "cs_overhead_ms": off_cpu, "cs_overhead_wall_ms": off_wall,
            "cs_modifier_ms": on_cpu - off_cpu, "cs_only_smooth_ms": smooth_cpu - off_cpu,
            "cs_repeats": n - 1}


def cmd_time(opts):
    Vb, faces, free, ob, md, info = setup(opts["--bind"], opts["--patch"], opts["--iterations"],
                                          opts["--group"])
    Vf, _, ff = read_obj(opts["--frame"])
    if len(Vf) != len(Vb) or ff != faces:
        raise SystemExit("corrective_smooth.py: %s: topology differs from the bind's" % opts["--frame"])
    r = time_cs(ob, md, Vf, opts["--repeats"])
    print("cs_info %s; Blender %s, %d thread(s)" % (info, bpy.app.version_string,
                                                   bpy.context.scene.render.threads))
    print("cs_vertices %d" % len(Vb))
    print("cs_free_vertices %d" % len(free))
    for k, v in r.items():
        print("%s %.3f" % (k, v))


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if not argv or argv[0] not in ("slide", "time"):
        raise SystemExit(__doc__)
    opts = {"--iterations": 10, "--repeats": 9, "--group": "free", "frames": []}
    i = 1
    while i < len(argv):
        a = argv[i]
        if a in ("--bind", "--patch", "-o", "--frame", "--group"):
            opts[a] = argv[i + 1]
            i += 2
        elif a in ("--iterations", "--repeats"):
            opts[a] = int(argv[i + 1])
            i += 2
        elif a.startswith("-"):
            raise SystemExit("corrective_smooth.py: unknown option %s" % a)
        else:
            opts["frames"].append(a)
            i += 1
    if opts["--group"] not in ("free", "patch", "mesh"):
        raise SystemExit("corrective_smooth.py: --group free|patch|mesh")
    need = ["--bind", "--patch"] + (["-o"] if argv[0] == "slide" else ["--frame"])
    for k in need:
        if k not in opts:
            raise SystemExit("corrective_smooth.py %s: %s is required" % (argv[0], k))
    if argv[0] == "slide":
        if not opts["frames"]:
            raise SystemExit("corrective_smooth.py slide: no frames")
        cmd_slide(opts)
    else:
        cmd_time(opts)


main()
