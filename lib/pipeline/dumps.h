// --dump and --preview: the images a TD opens to see why a patch slid the way it did
// (README "Dumps"). Each call writes the files of one mesh (the bind or one frame).
//
// One single-part EXR per patch and image, named after the mesh file's stem (its file name
// without folder and last extension, so a frame's padding is kept) and the patch index padded to
// three digits (patches are ordered as in BindSetup):
//   DIR/bind.patch000.id.exr     DIR/bind.patch000.geom.exr          the bind
//   DIR/f0003.patch000.id.exr    DIR/f0003.patch000.geom.exr         frame frames/f0003.obj
//   PREVIEW_DIR/f0003.patch000.png                                   its preview
// Skipped patches (nothing slides) get no files. The same inputs give the same bytes, whatever
// the thread count: no time stamps, no unordered containers.
#pragma once

#include <string>
#include <vector>

#include "core/types.h"
#include "locate/id_raster.h"
#include "pipeline/bind_setup.h"
#include "pipeline/slide_frame.h"

namespace skinslide {

/// The default side of the preview PNGs in pixels (--preview-size).
constexpr int kPreviewSize = 1024;

struct DumpOptions {
  int id_image_size = kLookupSize;  ///< side of the ID images in pixels (--lookup-size)
  int geometry_size = 0;            ///< side of the geometry images in texels; 0 = id_image_size
  int preview_size = kPreviewSize;  ///< side of the preview PNGs in pixels, >= 16
};

/// The stem a mesh path's dumps are named after: "frames/f0003.obj" -> "f0003".
std::string dump_stem(const std::string& mesh_path);

/// "DIR/STEM.patchKKK.SUFFIX", e.g. dump_path("out", "f0003", 2, "id.exr") =
/// "out/f0003.patch002.id.exr".
std::string dump_path(const std::string& dir, const std::string& stem, int patch,
                      const std::string& suffix);

/// Rejects frame paths whose dumps would overwrite others': a stem "bind" (the bind's dumps) or
/// two frames with the same stem. Call before reading any mesh.
/// \throw Error(Usage) naming the frame(s).
void check_dump_stems(const std::vector<std::string>& frame_paths);

/// The bind's dumps: per patch, the bind net's ID image at options.id_image_size (the image
/// point location would use for an identity frame) and its geometry image (P from
/// `bind_positions`, A). Creates `dump_dir` if needed.
/// \param bind_path the bind's file, recorded in the headers (skinslide.source)
/// \param bind_positions the bind's 3D positions (#V, mesh vertex ids)
/// \throw Error(Output) naming the file that cannot be written.
void write_bind_dumps(const std::string& dump_dir, const std::string& bind_path,
                      const BindSetup& setup, const Positions3& bind_positions,
                      const DumpOptions& options = {});

/// One frame's dumps: per patch, the ID image point location used (report.id_image, so the
/// frame must come from slide_frame(..., {.id_image_size = options.id_image_size})) and the frame
/// net's geometry image (P from `frame_positions`, A) with the slide field (slide.X, slide.Y; see
/// dump/slide_field.h). Creates `dump_dir` if needed.
/// \param reports slide_frame()'s FrameResult::patches, parallel to setup.patches
/// \throw Error(Output) naming the file; Error(Internal) when an ID image was not kept.
void write_frame_dumps(const std::string& dump_dir, const std::string& frame_path,
                       const BindSetup& setup, const Positions3& frame_positions,
                       const std::vector<PatchFrameReport>& reports,
                       const DumpOptions& options = {});

/// One frame's previews: per patch, preview_image() of the bind and frame nets with the patch's
/// free vertices as the moved ones, as PNG. Creates `preview_dir` if needed.
/// \throw Error(Output) naming the file.
void write_previews(const std::string& preview_dir, const std::string& frame_path,
                    const BindSetup& setup, const std::vector<PatchFrameReport>& reports,
                    const DumpOptions& options = {});

}  // namespace skinslide
