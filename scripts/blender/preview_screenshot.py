"""Draws Blender's window with the live preview on to a PNG (data/blender_preview.png): the tube
of preview_time.py bent by its armature, its skin (a UV grid) slid on the copy '<Tube> live',
the tube itself drawn as a wire over it, and the Skin Slide panel with the update's time.
Blender draws its UI only with a display, so run it under Xvfb:

    xvfb-run -s "-screen 0 1280x800x24" blender --factory-startup -noaudio \\
        --python scripts/blender/preview_screenshot.py -- build/python data/blender_preview.png
"""
import os
import sys

import bpy

module_dir, out = sys.argv[sys.argv.index("--") + 1:]
sys.path[:0] = [os.path.dirname(os.path.abspath(__file__)), module_dir]
import preview_time  # noqa: E402 (the tube and its rig)
import skinslide_addon  # noqa: E402

FRAMES = 12


def scene():
    bpy.context.preferences.view.show_splash = False  # read before the splash would open
    for obj in list(bpy.data.objects):  # the default cube, camera and light
        bpy.data.objects.remove(obj)
    skinslide_addon.register()
    bpy.context.scene.frame_start, bpy.context.scene.frame_end = 1, FRAMES
    tube, positions, _ = preview_time.cylinder(48, 41)
    preview_time.rig(tube, positions, FRAMES)
    bpy.data.objects["Rig"].hide_set(True)  # hidden, still posing the tube
    grid = bpy.data.images.new("grid", 1024, 1024)
    grid.generated_type = "COLOR_GRID"
    material = bpy.data.materials.new("skin")
    material.use_nodes = True
    texture = material.node_tree.nodes.new("ShaderNodeTexImage")
    texture.image = grid
    tube.data.materials.append(material)
    tube.select_set(True)
    bpy.context.view_layer.objects.active = tube
    bpy.context.scene.frame_set(FRAMES)
    tube.skinslide.live_preview = True
    bpy.context.scene.frame_set(FRAMES)  # a warm update: the time the panel shows


def frame_view(window):
    view = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    space = view.spaces[0]
    space.shading.type = "SOLID"
    space.shading.color_type = "TEXTURE"
    space.overlay.show_floor = space.overlay.show_axis_x = space.overlay.show_axis_y = False
    region = next(r for r in view.regions if r.type == "WINDOW")
    with bpy.context.temp_override(window=window, area=view, region=region):
        bpy.ops.view3d.view_axis(type="TOP")
        bpy.ops.view3d.view_selected()
    space.region_3d.view_distance *= 0.8


def capture():
    window = bpy.context.window_manager.windows[0]
    props = max((a for a in window.screen.areas if a.type == "PROPERTIES"),
                key=lambda a: a.width * a.height)
    props.spaces[0].context = "OBJECT"
    region = next(r for r in props.regions if r.type == "WINDOW")
    with bpy.context.temp_override(window=window, area=props, region=region):
        for _ in range(3):  # down to the Skin Slide panel, below the object's own
            bpy.ops.view2d.scroll_down(page=True)
    frame_view(window)
    bpy.app.timers.register(lambda: save(window), first_interval=1.0)


def save(window):
    settings = bpy.context.scene.render.image_settings  # what the screenshot is written with
    settings.file_format, settings.color_mode, settings.compression = "PNG", "RGB", 100
    with bpy.context.temp_override(window=window):
        bpy.ops.screen.screenshot(filepath=out)
    bpy.ops.wm.quit_blender()


scene()
bpy.app.timers.register(capture, first_interval=2.0)
