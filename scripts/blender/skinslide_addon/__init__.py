"""skinslide in Blender: slides the skin of a deformed mesh (armature, shape keys, any modifier)
over a frame range and bakes the result onto a copy that plays it back: a PC2 point cache played
by a Mesh Cache modifier (point_cache.py), or shape keys for short ranges. Or live: the current
frame slid on every frame change and every edit of the inputs, shown on a copy (live.py).

The slide is the skinslide Python module's (lib/python), the same bits as the command line on
the positions Blender evaluates. Install: scripts/blender/README.md.
"""

bl_info = {
    "name": "skinslide",
    "author": "skinslide",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Object > Skin Slide",
    "description": "Slide the skin of a deformed mesh and bake it to a point cache",
    "category": "Animation",
}

import concurrent.futures
import os
import sys

import bmesh
import bpy
import numpy as np

# Where the module is looked for when `import skinslide` alone fails: SKINSLIDE_PYTHONPATH, then
# the add-on's own folder (a copy of build/python/skinslide*.so put beside this file).
for _folder in (os.environ.get("SKINSLIDE_PYTHONPATH", ""), os.path.dirname(__file__)):
    if _folder and _folder not in sys.path:
        sys.path.append(_folder)
try:
    import skinslide
except ImportError:  # the panel says so; the operator refuses to run
    skinslide = None

from . import live, point_cache  # noqa: E402

SLID_SUFFIX = " slid"     # the baked copy is named after the object
KEY_PREFIX = "skinslide"  # its shape keys: skinslide.0001, ...


# ---- Settings -----------------------------------------------------------------------------------

# The options as the module declares them (name, default, range or words, help; the run's
# strength and method, then each method's): none of them is written again here.
OPTION_SPECS = skinslide.option_specs() if skinslide is not None else []


def _option_property(spec):
    """The Blender property of one option."""
    common = {"name": spec["name"].replace("_", " ").capitalize(), "description": spec["help"],
              "default": spec["default"], "update": live.settings_changed}
    if spec["type"] == "word":
        return bpy.props.EnumProperty(items=[(w, w.capitalize(), "") for w in spec["choices"]],
                                      **common)
    if spec["type"] == "int":
        return bpy.props.IntProperty(min=spec["min"], max=spec["max"], **common)
    return bpy.props.FloatProperty(min=spec["min"], max=spec["max"],
                                   soft_max=min(spec["max"], 1.0), precision=6, **common)


def _group_items(self, context):
    obj = context.object
    names = [g.name for g in obj.vertex_groups] if obj else []
    return [("", "(none)", "")] + [(n, n, "") for n in names]


# Solver internals, folded under the panel's Advanced: the options whose spec says "research"; a
# module from before that key, these (every paper option but the method itself).
ELASTIC_INTERNALS = {"rotation_fits", "max_iterations", "tolerance", "convergence", "blend",
                     "ease_in"}


def is_research(spec):
    """Whether an option is a solver internal rather than an artist's choice."""
    fallback = spec["method"] == "paper" or (spec["method"] == "elastic" and
                                             spec["name"] in ELASTIC_INTERNALS)
    return spec.get("research", fallback)


_changed = live.settings_changed  # every input's update: the live preview follows it


class SkinslideSettings(bpy.types.PropertyGroup):
    patch_source: bpy.props.EnumProperty(
        name="Patch", description="Which faces slide", update=_changed,
        items=[("SELECTION", "Face selection", "The faces selected in Edit Mode"),
               ("FACE_MAP", "Face map", "The faces of a face map"),
               ("VERTEX_GROUP", "Vertex group", "The faces whose every corner is in the group")])
    patch_face_map: bpy.props.StringProperty(name="Face map", update=_changed)
    patch_group: bpy.props.StringProperty(name="Patch group", update=_changed)
    pin_group: bpy.props.StringProperty(
        name="Pins", description="Vertices of this group do not slide; the skin around them does",
        update=_changed)
    weight_group: bpy.props.StringProperty(
        name="Weights", description="Slide weight per vertex (0 stays, 1 slides); none: 1",
        update=_changed)
    live_preview: bpy.props.BoolProperty(
        name="Live preview", update=live.toggled,
        description="Slide the current frame on every frame change and every edit, shown on a "
                    "copy '<object> live' (the object drawn as a wire over it); nothing is written")
    live_error: bpy.props.StringProperty(name="Live preview error",
                                         description="Why the live preview stopped")
    live_copy: bpy.props.PointerProperty(type=bpy.types.Object, name="Live copy")
    live_display: bpy.props.StringProperty(
        name="Display before the preview", description="The object's display type to restore")
    frame_start: bpy.props.IntProperty(name="Start", default=1)
    frame_end: bpy.props.IntProperty(name="End", default=250)
    use_scene_range: bpy.props.BoolProperty(name="Scene range", default=True)
    bake_to: bpy.props.EnumProperty(
        name="Bake to", default="PC2",
        items=[("PC2", "Point cache", "A PC2 file played by a Mesh Cache modifier: beside the "
                "saved .blend, or in the cache folder"),
               ("SHAPE_KEYS", "Shape keys", "One shape key a frame, kept in the .blend: for short "
                "ranges")])
    cache_folder: bpy.props.StringProperty(
        name="Cache folder", subtype="DIR_PATH",
        description="Where the PC2 goes (<object>_slid.pc2); empty: beside the .blend")


# The window over the range's neighbouring frames (--window, --window-ends), declared by the
# module as well: what slide_sequence takes.
SEQUENCE_SPECS = skinslide.sequence_option_specs() if skinslide is not None else []

for _spec in OPTION_SPECS + SEQUENCE_SPECS:
    SkinslideSettings.__annotations__[_spec["name"]] = _option_property(_spec)


def slider_options(s):
    """The Slider keyword options of the settings `s`: those of its method that were set. The
    others keep the library's defaults to the bit (a float property holds a float32)."""
    return {spec["name"]: getattr(s, spec["name"]) for spec in OPTION_SPECS
            if spec["method"] == s.method and s.is_property_set(spec["name"])}


# ---- The bake ---------------------------------------------------------------------------------

def mesh_arrays(mesh):
    """Positions (V, 3) float64, and faces as a flat vertex list with sizes."""
    positions = np.empty(3 * len(mesh.vertices), dtype=np.float32)
    mesh.vertices.foreach_get("co", positions)
    face_vertices = np.empty(len(mesh.loops), dtype=np.int32)
    mesh.polygons.foreach_get("vertices", face_vertices)
    face_sizes = np.empty(len(mesh.polygons), dtype=np.int32)
    mesh.polygons.foreach_get("loop_total", face_sizes)
    return positions.reshape(-1, 3).astype(np.float64), face_vertices, face_sizes


def group_weights(obj, name):
    """Per vertex its weight in vertex group `name` (0 where not in it); ValueError when the
    object has no such group."""
    if name not in obj.vertex_groups:
        raise ValueError(f"no vertex group named '{name}'")
    index = obj.vertex_groups[name].index
    weights = np.zeros(len(obj.data.vertices))
    for v in obj.data.vertices:
        for g in v.groups:
            if g.group == index:
                weights[v.index] = g.weight
    return weights


def patch_faces(obj, s):
    """The face ids that slide, by the settings' patch source."""
    mesh = obj.data
    if s.patch_source == "SELECTION" and obj.mode == "EDIT":  # the edit mesh's, live
        faces = bmesh.from_edit_mesh(mesh).faces
        faces.index_update()
        return np.array([f.index for f in faces if f.select], dtype=np.int32)
    if s.patch_source == "SELECTION":
        selected = np.zeros(len(mesh.polygons), dtype=bool)
        mesh.polygons.foreach_get("select", selected)
        return np.flatnonzero(selected)
    if s.patch_source == "FACE_MAP":
        face_map = obj.face_maps.get(s.patch_face_map)
        if face_map is None or not mesh.face_maps:
            raise ValueError(f"no face map named '{s.patch_face_map}'")
        values = np.array([d.value for d in mesh.face_maps[0].data])
        return np.flatnonzero(values == face_map.index)
    if s.patch_group not in obj.vertex_groups:
        raise ValueError(f"no vertex group named '{s.patch_group}'")
    inside = group_weights(obj, s.patch_group) > 0
    return np.array([p.index for p in mesh.polygons if all(inside[v] for v in p.vertices)],
                    dtype=np.int32)


def mesh_vertex_count(obj):
    """The object's vertex count now (in Edit Mode, the edit mesh's)."""
    if obj.mode == "EDIT":
        return len(bmesh.from_edit_mesh(obj.data).verts)
    return len(obj.data.vertices)


def slider_mesh_arguments(obj, s):
    """The Slider's arguments read from the mesh: bind, faces, patch, pins and weights."""
    positions, face_vertices, face_sizes = mesh_arrays(obj.data)
    faces = patch_faces(obj, s)
    if len(faces) == 0:
        raise ValueError("the patch has no faces: select some, or choose a face map or group")
    arguments = {"bind": positions, "faces": face_vertices, "patches": faces,
                 "face_sizes": face_sizes}
    if s.pin_group:
        arguments["pins"] = np.flatnonzero(group_weights(obj, s.pin_group) > 0)
    if s.weight_group:
        arguments["weights"] = np.clip(group_weights(obj, s.weight_group), 0.0, 1.0)
    return arguments


def slider_settings(s):
    """The Slider's arguments read from the settings: strength, method and its options."""
    return {"strength": s.strength, "method": s.method, **slider_options(s)}


def new_slider(mesh_arguments, settings):
    return skinslide.Slider(threads=os.cpu_count() or 1, **mesh_arguments, **settings)


def make_slider(obj, s):
    return new_slider(slider_mesh_arguments(obj, s), slider_settings(s))


def sequence_options(s):
    """The settings' window and where it ends, when the method takes them and a window is set
    (the command line refuses them with the paper method, and --window-ends without --window)."""
    if not SEQUENCE_SPECS or any(spec["method"] != s.method for spec in SEQUENCE_SPECS) or \
            s.window == 0:
        return {}
    return {spec["name"]: getattr(s, spec["name"]) for spec in SEQUENCE_SPECS}


def slide_poses(slider, poses, sequence, wm):
    """The range's poses slid, each to the bits of a serial slide: frame by frame on every core
    (the module releases the GIL), or as one sequence with a window over the neighbouring frames
    (the command line's --window and --window-ends on the same frames)."""
    if sequence:
        return list(slider.slide_sequence(poses, threads=os.cpu_count() or 1, **sequence)[0])
    slid = [None] * len(poses)
    with concurrent.futures.ThreadPoolExecutor(os.cpu_count() or 1) as pool:
        jobs = {pool.submit(slider.slide, pose): k for k, pose in enumerate(poses)}
        for done, job in enumerate(concurrent.futures.as_completed(jobs)):
            slid[jobs[job]] = job.result()[0]
            wm.progress_update(len(poses) + done + 1)
    return slid


def evaluated_positions(obj, depsgraph, vertex_count):
    """The object's mesh as the depsgraph evaluates it (armature, shape keys, modifiers)."""
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        if len(mesh.vertices) != vertex_count:
            raise ValueError(f"a modifier changes the vertex count ({vertex_count} -> "
                             f"{len(mesh.vertices)}): skinslide needs the mesh's own vertices")
        co = np.empty(3 * vertex_count, dtype=np.float32)
        mesh.vertices.foreach_get("co", co)
    finally:
        evaluated.to_mesh_clear()
    return co.reshape(-1, 3).astype(np.float64)


def baked_copy(context, obj):
    """A copy of the object's undeformed mesh, without modifiers or shape keys, for the baked
    slide: replaced when it exists."""
    name = obj.name + SLID_SUFFIX
    old = bpy.data.objects.get(name)
    if old is not None:
        bpy.data.objects.remove(old)
    mesh = obj.data.copy()
    mesh.name = name
    copy = bpy.data.objects.new(name, mesh)
    context.collection.objects.link(copy)
    if mesh.shape_keys:  # the source's keys pose the source; the copy plays back the slide
        copy.shape_key_clear()
    copy.matrix_world = obj.matrix_world.copy()
    return copy


def write_shape_keys(copy, frames, slid):
    """One shape key per frame, value 1 on its frame and 0 on the frames beside it."""
    copy.shape_key_add(name="Basis", from_mix=False)
    for frame, positions in zip(frames, slid):
        key = copy.shape_key_add(name=f"{KEY_PREFIX}.{frame:04d}", from_mix=False)
        key.data.foreach_set("co", positions.astype(np.float32).ravel())
        for f, value in ((frame - 1, 0.0), (frame, 1.0), (frame + 1, 0.0)):
            key.value = value
            key.keyframe_insert("value", frame=f)


def bake_result(context, obj, frames, slid, path):
    """The slid frames onto a fresh copy '<object> slid': with a cache `path`, a PC2 there and a
    Mesh Cache modifier playing it; else shape keys. Returns what to add to the report."""
    if path is None:
        write_shape_keys(baked_copy(context, obj), frames, slid)
        return ""
    point_cache.write_pc2(skinslide, path, frames, slid)
    point_cache.add_mesh_cache(baked_copy(context, obj), path, frames[0])
    return f", played by a Mesh Cache modifier from {path}"


class SKINSLIDE_OT_bake(bpy.types.Operator):
    """Slide the skin of the active mesh over the frame range and bake it onto a copy named
    '<object> slid': a PC2 point cache played by a Mesh Cache modifier, or shape keys"""
    bl_idname = "object.skinslide_bake"
    bl_label = "Bake skin slide"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return context.object is not None and context.object.type == "MESH"

    def execute(self, context):
        if skinslide is None:
            self.report({"ERROR"}, "the skinslide module cannot be imported: see "
                                   "scripts/blender/README.md")
            return {"CANCELLED"}
        obj = context.object
        s = obj.skinslide
        scene = context.scene
        first, last = ((scene.frame_start, scene.frame_end) if s.use_scene_range
                       else (s.frame_start, s.frame_end))
        frames = list(range(first, last + 1))
        if obj.mode == "EDIT":  # the face selection is the mesh's once out of Edit Mode
            bpy.ops.object.mode_set(mode="OBJECT")
        wm = context.window_manager
        wm.progress_begin(0, 2 * len(frames))
        current = scene.frame_current
        live.pause(True)  # the preview does not follow the bake's frames
        try:
            # Where the cache goes, known before any frame is slid (an unsaved .blend refuses).
            path = point_cache.cache_path(obj, s.cache_folder) if s.bake_to == "PC2" else None
            slider = make_slider(obj, s)
            poses = []
            for k, frame in enumerate(frames):
                scene.frame_set(frame)
                poses.append(evaluated_positions(obj, context.evaluated_depsgraph_get(),
                                                 slider.vertex_count))
                wm.progress_update(k + 1)
            slid = slide_poses(slider, poses, sequence_options(s), wm)
            baked = bake_result(context, obj, frames, slid, path)
        except (skinslide.Error, ValueError, OSError) as e:
            self.report({"ERROR"}, f"skinslide: {e}")
            return {"CANCELLED"}
        finally:
            live.pause(False)
            scene.frame_set(current)
            wm.progress_end()
        self.report({"INFO"}, f"skinslide: {len(frames)} frames baked into "
                              f"'{obj.name}{SLID_SUFFIX}'{baked}")
        return {"FINISHED"}


# ---- The panel --------------------------------------------------------------------------------

def _method_options(s, research):
    """The specs the panel draws for the settings' method: the artist's, or the internals."""
    return [spec for spec in OPTION_SPECS
            if spec["method"] == s.method and is_research(spec) == research]


def draw_live(layout, obj, s, scene):
    """The preview's toggle, its last update's time (or why it is slow), its error."""
    col = layout.column()
    col.prop(s, "live_preview", icon="PLAY" if not s.live_preview else "PAUSE")
    for text, icon in live_lines(s, live.STATS.get(obj.name), live.frame_ms(scene)):
        col.label(text=text, icon=icon)


def live_lines(s, stats, frame_ms):
    """What the panel says of the preview, (text, icon) a line: the last update's time, or that
    it is slower than the frame rate; its split; that a windowed bake can differ; the error."""
    lines = []
    if s.live_preview and stats:
        total = stats["total_ms"]
        lines.append((f"Slower than the frame rate: {total:.1f} ms an update, {frame_ms:.1f} ms "
                      f"a frame", "ERROR") if total > frame_ms else
                     (f"{total:.1f} ms an update", "TIME"))
        lines.append((f"slide {stats['slide_ms']:.1f} ms, Blender "
                      f"{stats['evaluate_ms'] + stats['write_ms']:.1f} ms", "NONE"))
    if s.live_preview and s.method == "elastic" and s.window > 0:
        lines.append(("The preview slides each frame alone: a windowed bake can differ", "INFO"))
    if s.live_error:
        lines.append((s.live_error, "ERROR"))
    return lines


class SKINSLIDE_PT_panel(bpy.types.Panel):
    bl_label = "Skin Slide"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "object"

    @classmethod
    def poll(cls, context):
        return context.object is not None and context.object.type == "MESH"

    def draw(self, context):
        layout = self.layout
        obj = context.object
        s = obj.skinslide
        if skinslide is None:
            layout.label(text="The skinslide module is not found", icon="ERROR")
        col = layout.column()
        col.prop(s, "patch_source")
        if s.patch_source == "FACE_MAP":
            col.prop_search(s, "patch_face_map", obj, "face_maps")
        elif s.patch_source == "VERTEX_GROUP":
            col.prop_search(s, "patch_group", obj, "vertex_groups")
        col.prop_search(s, "pin_group", obj, "vertex_groups")
        col.prop_search(s, "weight_group", obj, "vertex_groups")
        col.separator()
        for spec in OPTION_SPECS:  # strength, method
            if spec["method"] is None:
                col.prop(s, spec["name"])
        for spec in _method_options(s, research=False):  # the quality dial, if the method has one
            col.prop(s, spec["name"])
        layout.separator()
        draw_live(layout, obj, s, context.scene)
        layout.separator()
        col = layout.column()
        for spec in SEQUENCE_SPECS:  # the window over the range and its ends
            if spec["method"] == s.method:
                col.prop(s, spec["name"])
        col.prop(s, "use_scene_range")
        row = col.row(align=True)
        row.enabled = not s.use_scene_range
        row.prop(s, "frame_start")
        row.prop(s, "frame_end")
        col.separator()
        col.prop(s, "bake_to")
        if s.bake_to == "PC2":
            col.prop(s, "cache_folder")
        layout.operator(SKINSLIDE_OT_bake.bl_idname, icon="RENDER_ANIMATION")


class SKINSLIDE_PT_advanced(bpy.types.Panel):
    """The method's solver internals: folded, their defaults are the library's."""
    bl_label = "Advanced"
    bl_parent_id = "SKINSLIDE_PT_panel"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "object"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        s = context.object.skinslide
        col = self.layout.column()
        for spec in _method_options(s, research=True):
            col.prop(s, spec["name"])


CLASSES = (SkinslideSettings, SKINSLIDE_OT_bake, SKINSLIDE_PT_panel, SKINSLIDE_PT_advanced)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Object.skinslide = bpy.props.PointerProperty(type=SkinslideSettings)
    live.register()


def unregister():
    live.unregister()
    del bpy.types.Object.skinslide
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
