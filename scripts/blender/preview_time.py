"""Times the add-on's live preview, and Blender's Corrective Smooth live on the same mesh
(scripts/blender/README.md "Live preview"): a tube of RINGS rings of SIDES vertices bent at its
middle by a two-bone armature, all but 10 rings at each end the patch (the defaults, 128 101
12: 10,112 free vertices of 12,928), the bend animated over FRAMES frames.

    taskset -c 0 blender -b --factory-startup -noaudio -t 1 --python-exit-code 1 \\
        --python scripts/blender/preview_time.py -- build/python [SIDES RINGS FRAMES]

Prints "key value" lines, medians over the warm frames (2..FRAMES), milliseconds:
  preview_METHOD_*: the preview (elastic, then paper). Its update as the panel splits it:
    set_up (the vertex count checked, the set-up's cache key), evaluate (the evaluated mesh's
    positions read), slide (Slider.slide), write (the copy's positions set), total; frame_set
    with the preview on and off (off: the scene's own evaluation, the armature); start:
    turning it on (the copy, the set-up, the first slide); edit: an edit of the settings that
    changes nothing (the Slider's arguments read again from the mesh, a weight group of every
    vertex among them), rebuild: one that changes the strength (the set-up built again), each
    whole and its set_up part.
  cs_*: Corrective Smooth (10 iterations, the patch's free vertices as its group, bound at the
    rest pose: scripts/corrective_smooth.py's settings) after the armature: frame_set with the
    modifier on and off, and their difference, the modifier's own cost.
"""
import math
import os
import statistics
import sys
import time

import bpy
import numpy as np

if __name__ == "__main__":
    sys.path[:0] = [os.path.dirname(os.path.abspath(__file__)),
                    sys.argv[sys.argv.index("--") + 1]]

import skinslide_addon  # noqa: E402
from skinslide_addon import live  # noqa: E402

LENGTH, RADIUS = 4.0, 0.4


def cylinder(sides, rings):
    """A tube along x, `rings` rings of `sides` vertices, quads between them, UVs unrolled; the
    faces between its 10th ring and its 10th from the end selected (the patch). Returns the
    object, its positions and the patch's free vertices."""
    x = np.repeat(np.linspace(-LENGTH / 2, LENGTH / 2, rings), sides)
    angle = np.tile(np.linspace(0, 2 * math.pi, sides, endpoint=False), rings)
    positions = np.stack([x, RADIUS * np.cos(angle), RADIUS * np.sin(angle)], axis=1)
    ring, side = np.meshgrid(np.arange(rings - 1), np.arange(sides), indexing="ij")
    a = ring * sides + side
    b = ring * sides + (side + 1) % sides
    quads = np.stack([a, b, b + sides, a + sides], axis=-1).reshape(-1, 4)
    mesh = bpy.data.meshes.new("tube")
    mesh.vertices.add(len(positions))
    mesh.vertices.foreach_set("co", positions.astype(np.float32).ravel())
    mesh.loops.add(quads.size)
    mesh.loops.foreach_set("vertex_index", quads.astype(np.int32).ravel())
    mesh.polygons.add(len(quads))
    mesh.polygons.foreach_set("loop_start", np.arange(0, quads.size, 4, dtype=np.int32))
    mesh.polygons.foreach_set("loop_total", np.full(len(quads), 4, dtype=np.int32))
    mesh.update(calc_edges=True)
    # UVs: u along the tube, v around it (the seam's last column at v = 1).
    u = np.stack([ring, ring, ring + 1, ring + 1], axis=-1).reshape(-1) / (rings - 1)
    v = 1 - np.stack([side, side + 1, side + 1, side], axis=-1).reshape(-1) / sides
    mesh.uv_layers.new(name="UV").data.foreach_set("uv", np.stack([u, v], 1).ravel())
    obj = bpy.data.objects.new("Tube", mesh)
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    patch_rings = range(10, rings - 11)
    face_rings = np.arange(len(quads)) // sides
    mesh.polygons.foreach_set("select", np.isin(face_rings, patch_rings))
    free = np.arange((patch_rings[0] + 1) * sides, (patch_rings[-1] + 1) * sides)
    return obj, positions, free


def rig(obj, positions, frames):
    """Two bones along x, the second bending the tube's right half (a soft blend over the
    middle), animated from straight to 1.2 rad over the frames."""
    arm_data = bpy.data.armatures.new("rig")
    arm = bpy.data.objects.new("Rig", arm_data)
    bpy.context.scene.collection.objects.link(arm)
    bpy.context.view_layer.objects.active = arm
    bpy.ops.object.mode_set(mode="EDIT")
    root = arm_data.edit_bones.new("root")
    root.head, root.tail = (-LENGTH / 2, 0, 0), (0, 0, 0)
    tip = arm_data.edit_bones.new("tip")
    tip.head, tip.tail, tip.parent = (0, 0, 0), (LENGTH / 2, 0, 0), root
    bpy.ops.object.mode_set(mode="OBJECT")
    blend = np.clip(0.5 + positions[:, 0] / 0.6, 0.0, 1.0)
    for name, weights in (("root", 1 - blend), ("tip", blend)):
        group = obj.vertex_groups.new(name=name)
        for w in np.unique(weights):
            group.add(np.flatnonzero(weights == w).tolist(), float(w), "REPLACE")
    weights = obj.vertex_groups.new(name="slide")  # every vertex 1: read, the same slide
    weights.add(range(len(positions)), 1.0, "REPLACE")
    obj.skinslide.weight_group = "slide"
    obj.modifiers.new("armature", "ARMATURE").object = arm
    bone = arm.pose.bones["tip"]
    bone.rotation_mode = "XYZ"
    for frame in range(1, frames + 1):
        bone.rotation_euler = (0, 0, 1.2 * (frame - 1) / (frames - 1))
        bone.keyframe_insert("rotation_euler", frame=frame)
    bpy.context.view_layer.objects.active = obj


def frame_times(action=None):
    """frame_set's time at each warm frame (ms); `action()` after each, timed with it."""
    scene = bpy.context.scene
    scene.frame_set(1)
    times = []
    for frame in range(2, scene.frame_end + 1):
        t0 = time.perf_counter()
        scene.frame_set(frame)
        if action:
            action()
        times.append(1e3 * (time.perf_counter() - t0))
    return times


def edit_time(obj, edit):
    """The update after `edit` of the settings: its whole time and its set-up part (the
    arguments read again; the set-up rebuilt when they changed), ms."""
    t0 = time.perf_counter()
    edit()
    elapsed = 1e3 * (time.perf_counter() - t0)
    assert obj.skinslide.live_preview, obj.skinslide.live_error
    return elapsed, live.STATS[obj.name]["set_up_ms"]


def time_preview(obj, method):
    s = obj.skinslide
    s.method = method
    t0 = time.perf_counter()
    s.live_preview = True
    start_ms = 1e3 * (time.perf_counter() - t0)
    assert s.live_preview, s.live_error
    splits = []
    on = frame_times(lambda: splits.append(dict(live.STATS[obj.name])))
    edit_ms = edit_time(obj, lambda: setattr(s, "strength", s.strength))
    rebuild_ms = edit_time(obj, lambda: setattr(s, "strength", 0.9 if s.strength == 1 else 1.0))
    s.live_preview = False
    off = frame_times()
    out = {k: statistics.median(d[k] for d in splits) for k in splits[0]}
    out.update(start_ms=start_ms, edit_ms=edit_ms[0], edit_set_up_ms=edit_ms[1],
               rebuild_ms=rebuild_ms[0], rebuild_set_up_ms=rebuild_ms[1],
               frame_set_on_ms=statistics.median(on),
               frame_set_off_ms=statistics.median(off))
    return {f"preview_{method}_{k}": v for k, v in out.items()}


def time_corrective_smooth(obj, free):
    group = obj.vertex_groups.new(name="patch")
    group.add(free.tolist(), 1.0, "REPLACE")
    md = obj.modifiers.new("cs", "CORRECTIVE_SMOOTH")
    md.factor, md.iterations, md.scale, md.smooth_type = 0.5, 10, 1.0, "SIMPLE"
    md.use_only_smooth, md.use_pin_boundary = False, True
    md.vertex_group, md.rest_source = "patch", "BIND"
    bpy.context.scene.frame_set(1)  # the rest pose: the bind
    assert bpy.ops.object.correctivesmooth_bind(modifier=md.name) == {"FINISHED"}
    on = statistics.median(frame_times())
    md.show_viewport = False
    off = statistics.median(frame_times())
    md.show_viewport = True
    return {"cs_frame_set_on_ms": on, "cs_frame_set_off_ms": off, "cs_modifier_ms": on - off}


def main(sides, rings, frames):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    skinslide_addon.register()
    bpy.context.scene.frame_start, bpy.context.scene.frame_end = 1, frames
    obj, positions, free = cylinder(sides, rings)
    rig(obj, positions, frames)
    print(f"preview_info {len(positions)} vertices, {len(free)} free; Blender "
          f"{bpy.app.version_string}, {bpy.context.scene.render.threads} thread(s), "
          f"{len(os.sched_getaffinity(0))} core(s) allowed; {frames - 1} warm frames")
    times = {**time_preview(obj, "elastic"), **time_preview(obj, "paper"),
             **time_corrective_smooth(obj, free)}
    for key, value in times.items():
        print(f"{key} {value:.2f}")


if __name__ == "__main__":
    main(*(int(v) for v in sys.argv[sys.argv.index("--") + 2:] or (128, 101, 12)))
