"""The bake as a point cache: the slid frames written as one PC2 (the skinslide module's writer,
the command line's bytes) and played back by a Mesh Cache modifier on the baked copy. Blender's
own PC2 layout (lib/io/README.md "Point caches"): object-space positions, float32, sample 0 at
the bake's first frame, one sample a frame."""
import os

import bpy
import numpy as np

MODIFIER_NAME = "skinslide cache"


def cache_path(obj, folder):
    """Where `obj`'s cache goes: FOLDER/<object>_slid.pc2, or beside the .blend when FOLDER is
    empty (an unsaved .blend has no folder: ValueError)."""
    name = bpy.path.clean_name(obj.name + " slid") + ".pc2"
    if folder:
        return os.path.join(bpy.path.abspath(folder), name)
    if not bpy.data.filepath:
        raise ValueError("save the .blend first, or choose a cache folder: the PC2 is written "
                         "beside the .blend")
    return os.path.join(os.path.dirname(bpy.data.filepath), name)


def write_pc2(skinslide, path, frames, slid):
    """The slid positions (one (V, 3) array a frame of `frames`, consecutive) as a PC2:
    startFrame the first frame, sampleRate 1, each coordinate rounded to float32 once. Written
    atomically: a bake that fails leaves the previous cache as it was."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    skinslide.write_cache(path, np.stack(slid), start_frame=float(frames[0]), sample_rate=1.0)


def add_mesh_cache(copy, path, first_frame):
    """A Mesh Cache modifier on `copy` playing the PC2 at `path`, sample k on scene frame
    first_frame + k. Blender's quirks (lib/io/README.md): in Frame mode the modifier reads sample
    `scene frame x frame_scale - frame_start` whatever the header says, so frame_start is the
    first frame; the axes stay as they are (the cache is in object space, not turned Y-up)."""
    md = copy.modifiers.new(MODIFIER_NAME, "MESH_CACHE")
    md.cache_format = "PC2"
    # Relative to the .blend when saved ("//name.pc2"): the two move together.
    md.filepath = bpy.path.relpath(path) if bpy.data.filepath else path
    md.time_mode = "FRAME"
    md.play_mode = "SCENE"
    md.frame_start = float(first_frame)
    md.frame_scale = 1.0
    md.interpolation = "LINEAR"  # whole frames play a sample exactly; subframes blend two
    md.forward_axis, md.up_axis = "POS_Y", "POS_Z"
    md.flip_axis = set()
    md.deform_mode = "OVERWRITE"
    md.factor = 1.0
    return md
