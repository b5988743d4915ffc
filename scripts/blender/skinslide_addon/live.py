"""The live preview: the object's evaluated mesh slid at the current frame and shown on a copy,
'<object> live', updated on every frame change and every edit of the slide's inputs; no file is
written. The original object is never changed: it is drawn as a wire over the copy while the
preview is on (its own display restored when it is turned off, and the copy removed).

One frame at a time with Slider.slide, the bake's set-up on the bake's evaluated positions: the
copy holds the bake's float32 positions for that frame (never the bake's window). The set-up is
built once and rebuilt only when its arguments change (the cache key is the arguments themselves).
"""
import sys
import time

import bpy
import numpy as np
from bpy.app.handlers import persistent

LIVE_SUFFIX = " live"

# Per object name: the Slider's arguments and the Slider built from them, and the last update's
# timings (ms). A cache only: the settings (live_preview, live_copy) are the preview's state.
_sliders = {}
STATS = {}
_busy = False    # an update in progress: the depsgraph updates it causes are its own
_paused = False  # a bake is stepping through the frames


def pause(paused):
    global _paused
    _paused = paused


def frame_ms(scene):
    """The scene's frame time in milliseconds."""
    return 1000.0 * scene.render.fps_base / scene.render.fps


def _addon():
    """The add-on's own functions (the bake's mesh arrays, evaluation and Slider), imported when
    first used: the add-on imports this module before defining them."""
    return sys.modules[__package__]


def _evaluated_depsgraph(context):
    """The evaluated depsgraph, its evaluation's own update handlers ignored."""
    global _busy
    _busy = True
    try:
        return context.evaluated_depsgraph_get()
    finally:
        _busy = False


# ---- Starting and stopping ----------------------------------------------------------------------

def _make_copy(obj):
    """'<object> live': the object's mesh without shape keys or modifiers, in the object's
    collections, following its transform, neither selectable nor rendered."""
    name = obj.name + LIVE_SUFFIX
    old = bpy.data.objects.get(name)
    if old is not None:
        _remove_copy(old)
    mesh = obj.data.copy()
    mesh.name = name
    copy = bpy.data.objects.new(name, mesh)
    for collection in obj.users_collection:
        collection.objects.link(copy)
    if mesh.shape_keys:
        copy.shape_key_clear()
    copy.parent = obj
    copy.matrix_parent_inverse.identity()
    copy.hide_select = True
    copy.hide_render = True
    return copy


def _remove_copy(copy):
    mesh = copy.data
    bpy.data.objects.remove(copy)
    if mesh is not None and mesh.users == 0:
        bpy.data.meshes.remove(mesh)


def start(obj):
    """Turns the preview on: the copy made, the original drawn as a wire, the first update."""
    s = obj.skinslide
    s.live_error = ""
    s.live_display = obj.display_type
    s.live_copy = _make_copy(obj)
    obj.display_type = "WIRE"
    update(obj, _evaluated_depsgraph(bpy.context), edited=True)


def stop(obj, error=""):
    """Turns the preview off (with `error`, says why on the panel): the copy removed, the
    original's display restored."""
    s = obj.skinslide
    if error:
        s.live_error = error
    copy = s.live_copy
    s.live_copy = None
    if copy is not None:
        _remove_copy(copy)
    if s.live_display:
        obj.display_type = s.live_display
        s.live_display = ""
    _sliders.pop(obj.name, None)
    STATS.pop(obj.name, None)
    if s.live_preview:  # stopped by an error: the toggle follows (its update calls stop again)
        s.live_preview = False


# ---- An update ----------------------------------------------------------------------------------

def _same(a, b):
    """Whether two Slider argument lists are equal (arrays by value)."""
    if a.keys() != b.keys():
        return False
    return all(np.array_equal(a[k], b[k]) if isinstance(a[k], np.ndarray) else a[k] == b[k]
               for k in a)


def _slider(obj, edited):
    """The object's Slider, rebuilt when its arguments changed. The mesh's arguments (bind,
    faces, patch, pins, weights) are read again only after an edit; the settings' (strength,
    method, options) at every update, since they may be animated."""
    addon = _addon()
    cached = _sliders.get(obj.name)
    s = obj.skinslide
    settings = addon.slider_settings(s)
    if cached is not None and not edited and _same(cached[1], settings):
        return cached[2]
    mesh = addon.slider_mesh_arguments(obj, s) if edited or cached is None else cached[0]
    if cached is not None and _same(cached[0], mesh) and _same(cached[1], settings):
        return cached[2]
    slider = addon.new_slider(mesh, settings)
    _sliders[obj.name] = (mesh, settings, slider)
    return slider


def _check_vertex_count(obj, copy):
    addon = _addon()
    count = addon.mesh_vertex_count(obj)
    if count != len(copy.data.vertices):
        raise ValueError(f"the mesh now has {count} vertices, the preview was started with "
                         f"{len(copy.data.vertices)}: turn the preview on again")


def update(obj, depsgraph, edited):
    """Slides the object's evaluated mesh at the current frame onto its copy. An error stops
    the preview and is named on the panel."""
    global _busy
    addon = _addon()
    copy = obj.skinslide.live_copy
    if copy is None:
        return stop(obj, "the preview's copy was deleted")
    _busy = True
    try:
        t0 = time.perf_counter()
        _check_vertex_count(obj, copy)
        slider = _slider(obj, edited)
        t1 = time.perf_counter()
        positions = addon.evaluated_positions(obj, depsgraph, slider.vertex_count)
        t2 = time.perf_counter()
        slid = slider.slide(positions)[0]  # the GIL released
        t3 = time.perf_counter()
        copy.data.vertices.foreach_set("co", slid.astype(np.float32).ravel())
        copy.data.update()
        t4 = time.perf_counter()
    except (addon.skinslide.Error, ValueError) as e:
        return stop(obj, f"skinslide: {e}")
    except Exception as e:  # a bug: said on the panel, the preview stopped, Blender goes on
        return stop(obj, f"skinslide: internal error: {type(e).__name__}: {e}")
    finally:
        _busy = False
    STATS[obj.name] = {"set_up_ms": 1e3 * (t1 - t0), "evaluate_ms": 1e3 * (t2 - t1),
                       "slide_ms": 1e3 * (t3 - t2), "write_ms": 1e3 * (t4 - t3),
                       "total_ms": 1e3 * (t4 - t0)}


# ---- The handlers -------------------------------------------------------------------------------

def _previewed(scene):
    """The scene's objects whose preview is on; none while a bake steps through the frames or a
    render runs (a handler must not change data a render reads)."""
    if _paused or bpy.app.is_job_running("RENDER"):
        return []
    return [o for o in scene.objects if o.type == "MESH" and o.skinslide.live_preview]


def _sources(obj):
    """What the object's evaluated mesh depends on, as far as an edit goes: itself, its mesh
    and shape keys, the objects its modifiers read (an armature)."""
    ids = {obj, obj.data}
    if obj.data.shape_keys:
        ids.add(obj.data.shape_keys)
    for md in obj.modifiers:
        if getattr(md, "object", None) is not None:
            ids.add(md.object)
            ids.add(md.object.data)
    return ids


@persistent
def on_frame_change(scene, depsgraph):
    if _busy:
        return
    for obj in _previewed(scene):
        update(obj, depsgraph, edited=False)


@persistent
def on_depsgraph_update(scene, depsgraph):
    """An edit: of the mesh (selection, weights, groups), of the rig, of the settings."""
    if _busy:
        return
    updated = {u.id.original for u in depsgraph.updates}
    for obj in _previewed(scene):
        if updated & _sources(obj):
            update(obj, depsgraph, edited=True)


def settings_changed(settings, context):
    """A property update: the preview follows an edit of the settings at once."""
    obj = settings.id_data
    if settings.live_preview and settings.live_copy is not None and not _busy:
        update(obj, _evaluated_depsgraph(context), edited=True)


def toggled(settings, context):
    obj = settings.id_data
    if settings.live_preview and settings.live_copy is None:
        settings.live_error = ""
        start(obj)
    elif not settings.live_preview and settings.live_copy is not None:
        stop(obj)


def register():
    bpy.app.handlers.frame_change_post.append(on_frame_change)
    bpy.app.handlers.depsgraph_update_post.append(on_depsgraph_update)


def unregister():
    """The handlers removed and every preview stopped: no copy is left behind the add-on."""
    previewed = [o for o in bpy.data.objects
                 if o.type == "MESH" and o.skinslide.live_copy is not None]
    for obj in previewed:  # not while iterating bpy.data.objects: stop() removes from it
        stop(obj)
    for handlers, handler in ((bpy.app.handlers.frame_change_post, on_frame_change),
                              (bpy.app.handlers.depsgraph_update_post, on_depsgraph_update)):
        if handler in handlers:
            handlers.remove(handler)
