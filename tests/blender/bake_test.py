"""Headless Blender test of the add-on (run by tests/blender/bake.sh):

    blender -b --factory-startup -noaudio --python-exit-code 1 --python bake_test.py -- \
        ADDON_DIR MODULE_DIR SKINSLIDE WORK_DIR

A grid animated by an armature (a bone bends half of it) and by a shape key (a bulge), with a
face selection, a pin group and a weight group; baked by the add-on's operator with each method,
to a PC2 point cache played by a Mesh Cache modifier (the default) and to shape keys, and with a
window over the neighbouring frames (elastic). The baked
copy played back at every frame equals the command line's slide of the same evaluated frames
(OBJ files written here) within Blender's float32 positions: the cache's playback is exactly the
command's positions rounded to float32, and the add-on's PC2 is byte for byte the cache the
command writes when it slides a PC2 of those frames. A cache goes beside the saved .blend when
no folder is chosen; an unsaved .blend without a folder is refused.
"""
import pathlib
import sys

import bpy
import numpy as np

addon_dir, module_dir, skinslide_bin, work = sys.argv[sys.argv.index("--") + 1:]
sys.path[:0] = [addon_dir, module_dir, str(pathlib.Path(__file__).parent)]
import skinslide  # noqa: E402
import skinslide_addon  # noqa: E402
from scene import FRAMES, build_scene, played_back  # noqa: E402
import scene  # noqa: E402

work = pathlib.Path(work)


def command_slide(grid, method, case, window, ends):
    return scene.command_slide(skinslide_bin, grid, method, case, window, ends)


def check(grid, method, bake_to, folder, window=0, ends="one-sided", panel_window=None):
    """Bakes with the panel's window `panel_window` (default `window`) and compares with the
    command given `window`."""
    s = grid.skinslide
    s.method, s.pin_group, s.weight_group, s.strength = method, "pins", "slide", 0.9
    s.bake_to, s.cache_folder, s.window_ends = bake_to, folder, ends
    s.window = window if panel_window is None else panel_window
    assert bpy.ops.object.skinslide_bake() == {"FINISHED"}, method
    copy = bpy.data.objects[grid.name + skinslide_addon.SLID_SUFFIX]
    case = work / f"{method}_{bake_to}_window{window}_{ends}"
    frames = command_slide(grid, method, case, window, ends)
    if bake_to == "PC2":
        check_cache(copy, case, folder)
    else:
        assert copy.data.shape_keys and not copy.modifiers, "shape keys, no modifier"
    bind = skinslide_addon.mesh_arrays(grid.data)[0]
    diagonal = np.linalg.norm(bind.max(axis=0) - bind.min(axis=0))
    moved = error = 0.0
    for frame, path in zip(FRAMES, frames):
        expected = np.array([l.split()[1:4] for l in open(case / "slid" / path.name)
                             if l.startswith("v ")], dtype=np.float64)
        got = played_back(copy, frame)
        error = max(error, np.abs(got - expected).max())
        if bake_to == "PC2":  # the cache plays the command's positions rounded to float32, exactly
            assert np.array_equal(got, expected.astype(np.float32).astype(np.float64)), \
                f"{method} frame {frame}: off by {np.abs(got - expected).max()}"
        # Shape keys: Blender keeps float32 positions, and plays a key back as basis + (key -
        # basis).
        assert error <= 1e-6 * diagonal, f"{method} frame {frame}: off by {error}"
        moved = max(moved, np.abs(expected - played_back(grid, frame)).max())
    assert moved > 1e-3 * diagonal, f"{method}: the skin slid ({moved})"
    print(f"bake_test: {method}, {bake_to}, window {window} {ends}: {len(FRAMES)} frames played back as the command slid "
          f"them: largest difference {error:.3g} ({error / diagonal:.3g} of the diagonal; largest "
          f"slide {moved:.4g})")


def check_cache(copy, case, folder):
    """The copy plays its PC2 through a Mesh Cache modifier set as Blender needs it, and the PC2
    is the command's slid cache, byte for byte."""
    (md,) = copy.modifiers
    assert md.type == "MESH_CACHE" and md.cache_format == "PC2", md.type
    assert (md.time_mode, md.play_mode, md.frame_start, md.frame_scale) == \
        ("FRAME", "SCENE", FRAMES[0], 1.0), (md.time_mode, md.frame_start)
    assert (md.forward_axis, md.up_axis, md.deform_mode) == ("POS_Y", "POS_Z", "OVERWRITE")
    assert not copy.data.shape_keys, "a cached copy has no shape keys"
    path = pathlib.Path(bpy.path.abspath(md.filepath))
    if folder:
        assert path.parent == pathlib.Path(folder), (path, folder)
    else:  # beside the .blend, relative to it
        assert md.filepath == "//" + path.name and path.parent == work, md.filepath
    samples, header = skinslide.read_cache(str(path))
    assert header["frames"] == list(FRAMES) and header["sample_rate"] == 1, header
    ours = (case / "slid" / "shot.pc2").read_bytes()
    assert path.read_bytes() == ours, f"{path} is not the command's slid cache"


grid = build_scene()
# The default: a PC2 and a Mesh Cache modifier; an unsaved .blend needs a cache folder.
assert grid.skinslide.bake_to == "PC2"
try:
    bpy.ops.object.skinslide_bake()
    raise SystemExit("bake_test: a cache with neither a saved .blend nor a folder was baked")
except RuntimeError as e:  # operator reports of type ERROR raise in background mode
    assert "save the .blend first" in str(e), e
check(grid, "elastic", "PC2", str(work / "caches"))
check(grid, "paper", "SHAPE_KEYS", "")
bpy.ops.wm.save_as_mainfile(filepath=str(work / "scene.blend"))
check(grid, "paper", "PC2", "")  # beside the .blend
check(grid, "elastic", "SHAPE_KEYS", "")
check(grid, "elastic", "PC2", "", window=2)  # the command's --window over the same frames
check(grid, "elastic", "SHAPE_KEYS", "", window=1, ends="cycle")  # and --window-ends cycle
# A window left set on the panel is the elastic method's: paper bakes as the command without it.
check(grid, "paper", "PC2", "", panel_window=3, ends="cycle")
# An error is Blender's report, not a crash: a weight group that is gone (a KeyError's traceback
# before), a patch of no faces.
grid.skinslide.weight_group = "gone"
try:
    bpy.ops.object.skinslide_bake()
    raise SystemExit("bake_test: a missing weight group was not refused")
except RuntimeError as e:
    assert "no vertex group named 'gone'" in str(e), e
grid.skinslide.weight_group = "slide"
for p in grid.data.polygons:
    p.select = False
try:
    bpy.ops.object.skinslide_bake()
    raise SystemExit("bake_test: an empty patch was not refused")
except RuntimeError as e:
    assert "the patch has no faces" in str(e), e
print("bake_test: passed")
