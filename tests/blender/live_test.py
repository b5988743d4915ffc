"""Headless Blender test of the add-on's live preview (run by tests/blender/bake.sh live_test.py):

    blender -b --factory-startup -noaudio --python-exit-code 1 --python live_test.py -- \
        ADDON_DIR MODULE_DIR SKINSLIDE WORK_DIR

The bake test's grid (armature bend, shape key bulge, pins, weights). With the preview on, at
every frame the copy '<grid> live' holds the command line's slide of the same evaluated frame
rounded to float32, exactly, and the same bits as the add-on's baked PC2 (and the viewport's
depsgraph holds them after the frame change). An edit of the weight
group shows on the next frame, a new strength and a selection in Edit Mode at once; the panel
says when an update is slower than a frame; turned off, the copy is gone and the grid
deforms and draws as before. Errors stop the preview and are named on the panel (live_error):
an empty patch, a selection the library refuses (stray faces making a bow-tie), a weight group
deleted, the copy deleted, the mesh edited to another vertex count. The add-on disabled with the
preview on leaves nothing behind. Prints the time of each update.

Blender runs the depsgraph update handlers when it evaluates the scene after an edit (the
viewport's redraw); headless, view_layer.update() stands for that redraw.
"""
import pathlib
import sys

import bmesh
import bpy
import numpy as np

addon_dir, module_dir, skinslide_bin, work = sys.argv[sys.argv.index("--") + 1:]
sys.path[:0] = [addon_dir, module_dir, str(pathlib.Path(__file__).parent)]
import skinslide  # noqa: E402
import skinslide_addon  # noqa: E402
from skinslide_addon import live  # noqa: E402
import scene  # noqa: E402

work = pathlib.Path(work)
FRAMES = scene.FRAMES


def preview_positions(copy, frame=None):
    """The copy's positions (float32) at `frame` (None: as they are)."""
    if frame is not None:
        bpy.context.scene.frame_set(frame)
    co = np.empty(3 * len(copy.data.vertices), dtype=np.float32)
    copy.data.vertices.foreach_get("co", co)
    return co.reshape(-1, 3)


def drawn_positions(copy):
    """The copy as the viewport draws it: evaluated in the view layer's depsgraph as it stands
    (not evaluated again here)."""
    evaluated = copy.evaluated_get(bpy.context.view_layer.depsgraph)
    mesh = evaluated.to_mesh()
    co = np.empty(3 * len(mesh.vertices), dtype=np.float32)
    mesh.vertices.foreach_get("co", co)
    evaluated.to_mesh_clear()
    return co.reshape(-1, 3)


def command(grid, name, frames=FRAMES):
    """The command's slide of the grid's evaluated frames with the panel's settings, float32."""
    case = work / name
    paths = scene.command_slide(skinslide_bin, grid, "elastic", case, 0, "one-sided", frames)
    return {f: scene.slid_positions(case, p).astype(np.float32) for f, p in zip(frames, paths)}


def assert_equal(got, expected, what):
    assert got.shape == expected.shape, f"{what}: {got.shape} != {expected.shape}"
    assert np.array_equal(got, expected), \
        f"{what}: off by {np.abs(got.astype(np.float64) - expected).max()}"


def timing(grid):
    t = live.STATS[grid.name]
    return (f"{t['total_ms']:.2f} ms (slide {t['slide_ms']:.2f}, evaluate {t['evaluate_ms']:.2f}, "
            f"write {t['write_ms']:.2f}, set-up check {t['set_up_ms']:.2f})")


def check_preview(grid):
    """Frames 1..N with the preview on: the command's and the bake's positions."""
    s = grid.skinslide
    expected = command(grid, "live")
    s.bake_to, s.cache_folder = "PC2", str(work / "caches")
    assert bpy.ops.object.skinslide_bake() == {"FINISHED"}
    baked, _ = skinslide.read_cache(str(work / "caches" / "Grid_slid.pc2"))
    s.live_preview = True
    copy = bpy.data.objects[grid.name + live.LIVE_SUFFIX]
    assert s.live_copy == copy and grid.display_type == "WIRE" and not s.live_error
    assert copy.parent == grid and not copy.modifiers and not copy.data.shape_keys
    moved = 0.0
    for k, frame in enumerate(FRAMES):
        got = preview_positions(copy, frame)
        assert_equal(got, expected[frame], f"frame {frame} against the command")
        assert_equal(got, baked[k], f"frame {frame} against the bake")
        assert_equal(drawn_positions(copy), got, f"frame {frame} as drawn")
        own = scene.played_back(grid, frame).astype(np.float32)
        moved = max(moved, float(np.abs(got - own).max()))
        print(f"live_test: frame {frame}: the command's and the bake's float32 positions; "
              f"update {timing(grid)}")
    assert moved > 1e-2, f"the preview slid nothing ({moved})"
    return copy


def check_edits(grid, copy):
    """A weight edit shows on the next frame; a new strength at once."""
    before = preview_positions(copy, FRAMES[1])
    weights = grid.vertex_groups["slide"]
    weights.add(range(len(grid.data.vertices)), 0.25, "REPLACE")
    bpy.context.view_layer.update()  # the redraw after a weight-paint stroke
    expected = command(grid, "live_weights", frames=[FRAMES[2]])
    got = preview_positions(copy, FRAMES[2])
    assert_equal(got, expected[FRAMES[2]], "the next frame after a weight edit")
    assert not np.array_equal(preview_positions(copy, FRAMES[1]), before), "weights unchanged"
    print(f"live_test: a weight edit shows on the next frame; update {timing(grid)}")
    bpy.context.scene.frame_set(FRAMES[1])
    grid.skinslide.strength = 0.5  # the panel's field: the preview follows at once
    got = preview_positions(copy)
    expected = command(grid, "live_strength", frames=[FRAMES[1]])
    assert_equal(got, expected[FRAMES[1]], "a new strength")
    print(f"live_test: a new strength shows at once; update {timing(grid)}")


def check_edit_mode(grid, copy):
    """In Edit Mode the preview follows the selection as it is clicked (the edit mesh's), on
    what Blender evaluates there: the armature shown in Edit Mode."""
    grid.modifiers["armature"].show_in_editmode = True
    bpy.context.scene.frame_set(FRAMES[2])
    bpy.ops.object.mode_set(mode="EDIT")
    before = preview_positions(copy)
    edit_mesh = bmesh.from_edit_mesh(grid.data)
    for f in edit_mesh.faces:
        f.select = f.index >= 48
    bmesh.update_edit_mesh(grid.data)
    bpy.context.view_layer.update()  # the redraw after a click
    got = preview_positions(copy)
    expected = command(grid, "live_edit_mode", frames=[FRAMES[2]])
    assert_equal(got, expected[FRAMES[2]], "a selection in Edit Mode")
    assert not np.array_equal(got, before), "the selection changed nothing"
    bpy.ops.object.mode_set(mode="OBJECT")
    grid.modifiers["armature"].show_in_editmode = False
    print(f"live_test: a selection in Edit Mode shows at once; update {timing(grid)}")


def check_panel_lines(grid):
    """The panel's lines: the time, or that the update is slower than a frame; the window."""
    s = grid.skinslide
    stats = {"total_ms": 50.0, "slide_ms": 45.0, "evaluate_ms": 1.5, "write_ms": 0.5}
    slow = skinslide_addon.live_lines(s, stats, 1000 / 24)
    assert slow[0] == ("Slower than the frame rate: 50.0 ms an update, 41.7 ms a frame",
                       "ERROR"), slow
    assert slow[1] == ("slide 45.0 ms, Blender 2.0 ms", "NONE"), slow
    assert skinslide_addon.live_lines(s, stats, 1000 / 12)[0] == ("50.0 ms an update", "TIME")
    s.window = 2
    assert "a windowed bake can differ" in skinslide_addon.live_lines(s, stats, 100)[-1][0]
    s.window = 0
    internals = {"name": "tolerance", "method": "elastic"}
    assert skinslide_addon.is_research(internals)  # a module without the "research" key
    assert not skinslide_addon.is_research({**internals, "research": False})
    assert not skinslide_addon.is_research({"name": "strength", "method": None})


def check_off(grid, own, display):
    s = grid.skinslide
    s.live_preview = False
    assert s.live_copy is None and grid.name + live.LIVE_SUFFIX not in bpy.data.objects
    assert grid.name + live.LIVE_SUFFIX not in bpy.data.meshes, "the copy's mesh is left"
    assert grid.display_type == display, grid.display_type
    for frame in FRAMES:
        assert_equal(scene.played_back(grid, frame), own[frame], f"frame {frame} after the preview")
    print("live_test: turned off, the copy is gone and the grid deforms and draws as before")


def expect_stop(grid, display, cause, words):
    """The preview on, `cause()` done: it stops, and the panel names the error."""
    s = grid.skinslide
    s.live_error = ""
    s.live_preview = True
    cause()
    assert not s.live_preview, f"the preview goes on after: {words}"
    assert s.live_copy is None and grid.name + live.LIVE_SUFFIX not in bpy.data.objects
    assert grid.display_type == display
    assert words in s.live_error, f"'{s.live_error}' does not say '{words}'"
    print(f"live_test: stopped, the panel says: {s.live_error}")


def bowtie_faces(mesh):
    """The faces around a vertex's ring, less two of its own faces that share no edge: stray
    faces that make the vertex a bow-tie."""
    vertex_faces = {}
    for p in mesh.polygons:
        for v in p.vertices:
            vertex_faces.setdefault(v, []).append(p.index)
    edges = {p.index: {frozenset(e) for e in p.edge_keys} for p in mesh.polygons}
    v = next(v for v, fan in vertex_faces.items() if len(fan) == 4)
    fan = vertex_faces[v]
    ring = {f for u in (w for f in fan for w in mesh.polygons[f].vertices) for f in vertex_faces[u]}
    a, b = next((a, b) for a in fan for b in fan if a < b and not edges[a] & edges[b])
    return ring - {a, b}


def select(mesh, faces):
    for p in mesh.polygons:
        p.select = p.index in faces


def check_errors(grid, display):
    s = grid.skinslide
    mesh = grid.data
    patch = {p.index for p in mesh.polygons if p.select}
    select(mesh, set())
    expect_stop(grid, display, lambda: None, "the patch has no faces")
    select(mesh, patch)

    def stray_faces():
        select(mesh, bowtie_faces(mesh))
        bpy.context.view_layer.update()
    expect_stop(grid, display, stray_faces, "bow-tie")
    select(mesh, patch)

    doomed = grid.vertex_groups.new(name="doomed")
    doomed.add(range(len(mesh.vertices)), 0.5, "REPLACE")
    s.weight_group = "doomed"

    def delete_weights():
        grid.vertex_groups.remove(doomed)
        bpy.context.view_layer.update()
    expect_stop(grid, display, delete_weights, "no vertex group named 'doomed'")
    s.weight_group = "slide"

    def delete_copy():
        bpy.data.objects.remove(s.live_copy)
        bpy.context.scene.frame_set(FRAMES[1])
    expect_stop(grid, display, delete_copy, "the preview's copy was deleted")

    def add_vertices():
        bm = bmesh.new()
        bm.from_mesh(mesh)
        bmesh.ops.subdivide_edges(bm, edges=bm.edges[:2], cuts=1)
        bm.to_mesh(mesh)
        bm.free()
        mesh.update()
        bpy.context.scene.frame_set(FRAMES[0])  # the next frame: no redraw in between
    expect_stop(grid, display, add_vertices, "the mesh now has")


grid = scene.build_scene()
s = grid.skinslide
s.method, s.pin_group, s.weight_group, s.strength = "elastic", "pins", "slide", 0.9
display = grid.display_type
own = {frame: scene.played_back(grid, frame) for frame in FRAMES}
copy = check_preview(grid)
check_edits(grid, copy)
check_edit_mode(grid, copy)
check_panel_lines(grid)
grid.skinslide.strength = 0.9
check_off(grid, own, display)
check_errors(grid, display)
# Disabled with the preview on, the add-on leaves no copy and no handler behind.
grid.skinslide.live_preview = True
skinslide_addon.unregister()
assert grid.name + live.LIVE_SUFFIX not in bpy.data.objects and grid.display_type == display
assert live.on_frame_change not in bpy.app.handlers.frame_change_post
print("live_test: passed")
