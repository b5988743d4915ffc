"""Renders the add-on's panel to a PNG (README "In Blender"): Blender draws its UI only with a
display, so run it under Xvfb:

    xvfb-run -s "-screen 0 1700x2100x24" blender --factory-startup -noaudio \\
        --python scripts/blender/panel_screenshot.py -- build/python data/blender_panel.png
"""
import os
import sys

import bpy

module_dir, out = sys.argv[sys.argv.index("--") + 1:]
sys.path[:0] = [os.path.dirname(os.path.abspath(__file__)), module_dir]
import skinslide_addon  # noqa: E402

skinslide_addon.register()
bpy.ops.mesh.primitive_grid_add(x_subdivisions=16, y_subdivisions=8, size=2)
grid = bpy.context.object
grid.name = "Forearm"
grid.vertex_groups.new(name="pins")
grid.vertex_groups.new(name="slide")
grid.skinslide.pin_group = "pins"
grid.skinslide.weight_group = "slide"


def capture():
    window = bpy.context.window_manager.windows[0]
    screen = window.screen
    props = max((a for a in screen.areas if a.type == "PROPERTIES"),
                key=lambda a: a.width * a.height)
    props.spaces[0].context = "OBJECT"
    with bpy.context.temp_override(window=window, screen=screen, area=props):
        bpy.ops.screen.screenshot_area(filepath=out)
    bpy.ops.wm.quit_blender()


# A tall window: the Properties editor of the default layout then shows the object's panels and
# this one whole.
bpy.context.preferences.view.ui_scale = 1.2
bpy.app.timers.register(capture, first_interval=2.0)
