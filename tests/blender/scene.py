"""The blender tests' scene (bake_test.py, live_test.py): a grid bent by an armature and bulged
by a shape key, with a face selection, a pin group and a weight group; and the command line's
slide of the frames Blender evaluates from it."""
import math
import subprocess

import bpy
import numpy as np
import skinslide
import skinslide_addon

FRAMES = range(1, 5)


def build_scene():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    skinslide_addon.register()
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = FRAMES[0], FRAMES[-1]
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=16, y_subdivisions=8, size=2)
    grid = bpy.context.object
    grid.scale = (2, 1, 1)
    bpy.ops.object.transform_apply(scale=True)
    # A shape key: a bulge in the middle, keyed from 0 to 1.
    grid.shape_key_add(name="Basis")
    bulge = grid.shape_key_add(name="bulge")
    for v, k in zip(grid.data.vertices, bulge.data):
        k.co.z = v.co.z + 0.3 * math.exp(-4 * (v.co.x ** 2 + v.co.y ** 2))
    for frame, value in ((1, 0.0), (4, 1.0)):
        bulge.value = value
        bulge.keyframe_insert("value", frame=frame)
    # An armature of two bones along x; the second bends the grid's right half.
    bpy.ops.object.armature_add(location=(-2, 0, 0))
    arm = bpy.context.object
    bpy.ops.object.mode_set(mode="EDIT")
    root = arm.data.edit_bones[0]
    root.head, root.tail = (0, 0, 0), (2, 0, 0)
    bent = arm.data.edit_bones.new("tip")
    bent.head, bent.tail, bent.parent = (2, 0, 0), (4, 0, 0), root
    bpy.ops.object.mode_set(mode="OBJECT")
    for name, side in ((arm.data.bones[0].name, -1), ("tip", 1)):
        group = grid.vertex_groups.new(name=name)
        for v in grid.data.vertices:
            w = min(1.0, max(0.0, 0.5 + side * v.co.x))  # a soft blend over the middle
            if w > 0:
                group.add([v.index], w, "REPLACE")
    grid.modifiers.new("armature", "ARMATURE").object = arm
    tip = arm.pose.bones["tip"]
    tip.rotation_mode = "XYZ"
    for frame, angle in ((1, 0.0), (4, 1.0)):
        tip.rotation_euler = (0, 0, angle)
        tip.keyframe_insert("rotation_euler", frame=frame)
    # Controls: a pin and weights.
    pins = grid.vertex_groups.new(name="pins")
    pins.add([grid.data.vertices[60].index], 1.0, "REPLACE")
    slide = grid.vertex_groups.new(name="slide")
    for v in grid.data.vertices:
        slide.add([v.index], 0.5 + 0.5 * (v.index % 3 == 0), "REPLACE")
    # Every face but the first row is the patch.
    for p in grid.data.polygons:
        p.select = p.index >= 16
    bpy.context.view_layer.objects.active = grid
    grid.select_set(True)
    return grid


def write_obj(path, positions, mesh):
    with open(path, "w") as f:
        for x, y, z in positions:
            f.write(f"v {float(x)!r} {float(y)!r} {float(z)!r}\n")
        for p in mesh.polygons:
            f.write("f " + " ".join(str(v + 1) for v in p.vertices) + "\n")


def played_back(obj, frame):
    bpy.context.scene.frame_set(frame)
    return skinslide_addon.evaluated_positions(obj, bpy.context.evaluated_depsgraph_get(),
                                               len(obj.data.vertices))


def command_slide(skinslide_bin, grid, method, case, window, ends, frames=None):
    """The command line on the frames Blender evaluated (float32, written exactly): OBJ files,
    and the same frames as a PC2 (startFrame the first frame, rate 1). Returns the frame OBJs."""
    s = grid.skinslide
    frames = frames or FRAMES
    (case / "frames").mkdir(parents=True, exist_ok=True)
    bind, faces, sizes = skinslide_addon.mesh_arrays(grid.data)
    write_obj(case / "bind.obj", bind, grid.data)
    paths, poses = [], []
    for frame in frames:
        paths.append(case / "frames" / f"grid.{frame:04d}.obj")
        poses.append(played_back(grid, frame))
        write_obj(paths[-1], poses[-1], grid.data)
    skinslide.write_cache(str(case / "shot.pc2"), np.stack(poses), start_frame=frames[0])
    patch = skinslide_addon.patch_faces(grid, s)
    (case / "patch.txt").write_text(" ".join(map(str, patch)) + "\n")
    weights = skinslide_addon.group_weights(grid, "slide")
    (case / "weights.txt").write_text("".join(f"{w!r}\n" for w in weights))
    (case / "pins.txt").write_text("60\n")
    # The strength as the add-on holds it: a Blender float property is a float32 (0.9 is
    # 0.8999999761581421), and the command must get those bits to give the add-on's.
    strength = repr(float(s.strength))
    windowed = ["--window", str(window), "--window-ends", ends] if window else []
    for source in (paths, [case / "shot.pc2"]):
        subprocess.run([skinslide_bin, "-q", "--method", method, *windowed,
                        "--patch", case / "patch.txt",
                        "--weights", case / "weights.txt", "--pin", case / "pins.txt",
                        "--strength", strength, case / "bind.obj", *source, "-o", case / "slid"],
                       check=True)
    return paths


def slid_positions(case, path):
    """The command's slide of the frame file `path`: its OBJ's positions."""
    with open(case / "slid" / path.name) as f:
        return np.array([line.split()[1:4] for line in f if line.startswith("v ")],
                        dtype=np.float64)
