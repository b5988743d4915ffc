// What a run reads, writes and how it slides (README "Options"): the command line's options as
// plain data, which cli/ fills and run() (pipeline/run.h) reads; and the table (core/option.h) of
// the run's options both methods share, which the command line, the Python module and the
// Blender add-on read.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/option.h"
#include "core/types.h"
#include "io/mesh_file.h"
#include "locate/id_raster.h"
#include "pipeline/dumps.h"
#include "pipeline/options.h"
#include "pipeline/rig_frames.h"

namespace skinslide {

/// The widest --window: 100 frames on each side, four seconds of motion either way at 25 frames
/// a second; a slide that still jumps at that width is not the jitter a window smooths.
constexpr int kMaxWindow = 100;

/// Where a window's frames stop (--window-ends): at the sequence's first and last frames, whose
/// windows are then one-sided; or around a loop, the last frame followed by the first.
enum class WindowEnds { OneSided, Cycle };

/// What a run reads, writes and how it slides: the command line's options (README "Options") as
/// plain data, after the command line's own checks (conflicting options, ranges). Paths as given.
struct RunOptions {
  // Inputs
  std::string bind;                  ///< BIND: .obj, .gltf or .glb
  std::vector<std::string> patches;  ///< --patch files, in order; each file's patches separate
  std::vector<std::string> frames;   ///< FRAME files, in order; empty with `rig`
  std::string mesh;                  ///< --mesh (name, else index); empty = the only one
  /// --allow-uri-outside: trees a glTF's buffers may be read from besides its own folder.
  std::vector<std::string> allow_uri_outside;
  /// --animation (and --fps): BIND is a rigged glTF character, the frames its clip's samples.
  std::optional<RigOptions> rig;
  /// --format of the slid frames: "obj" or "glb" (a file a frame), "pc2" or "mdd" (one point
  /// cache); empty = "glb" for `rig`, the cache's own format for a cache FRAME (cache_frames.h).
  std::string format;
  /// --bind-is-frame: a BIND named as a member of the FRAME sequence (frame_plans.h) is meant.
  bool bind_is_frame = false;
  /// --fps with FRAME files written as one MDD cache: frame n is at n / fps seconds; 0 = none.
  double fps = 0;
  // Outputs
  /// Folder of the slid frames, created if missing; for a run writing one point cache, a path
  /// ending in the cache's extension (shot.pc2) names the cache itself (frame_plans.h).
  std::string output = "slid";
  std::string dump_dir;             ///< --dump: EXR images of the nets; empty = none
  std::string preview_dir;          ///< --preview: PNG pictures of the nets; empty = none
  int preview_size = kPreviewSize;  ///< side of the preview PNGs, pixels
  int lookup_size = kLookupSize;    ///< side of the dumps' ID images, pixels (--lookup-size)
  std::string report;               ///< --report JSON file; empty = none
  bool report_timings = true;       ///< false: --report-no-timings
  // Method
  SlideOptions slide;  ///< the method and its options
  /// --window N (elastic): each frame written at the mean of its own and its N neighbours' slides
  /// on each side (pipeline/frame_window.h); 0: each frame its own.
  int window = 0;
  WindowEnds window_ends = WindowEnds::OneSided;  ///< --window-ends
  // Controls (README "Controls"), read after the bind: their ids are checked against it.
  std::string weights;                      ///< --weights file; empty = none
  std::string weights_from_obj_color;       ///< "r", "g" or "b" of the OBJ bind; empty = none
  std::string weights_from_gltf_attribute;  ///< a vertex attribute of the glTF bind; empty = none
  double strength = SlideControls{}.strength;  ///< multiplies every weight
  std::string pin;                             ///< --pin file; empty = none
  std::vector<std::string> corners;            ///< --corners as given, each "a,b,c,d"
  std::vector<Index> outer_loop_vertices;      ///< --outer-loop-vertex, one per patch
  // Run
  unsigned threads = 0;      ///< frames (and patches) processed at once; 0 = usable_cores()
  std::string frame_ranges;  ///< --frames (pipeline/frame_ranges.h); empty = every frame
  bool keep_going = false;   ///< write every good frame and name every bad one
  /// A patch that did not converge (elastic stops other than "converged" and "at rest") fails
  /// its frame (exit 5) instead of being logged as not converged.
  bool require_converged = false;
  bool no_slide = false;  ///< read, check and write every frame unchanged (not with `rig`)
};

/// How the run reads BIND and every FRAME (--mesh, --allow-uri-outside).
MeshReadOptions mesh_read_options(const RunOptions& o);

/// The run's options both methods share and every client takes (the command line, the Python
/// module's Slider, the add-on): --strength, then --method.
template <>
const OptionTable<RunOptions>& option_table<RunOptions>();

/// --strength: RunOptions::strength.
const Option<RunOptions>& strength_option();

/// --method: which method slides, by its name (RunOptions::slide's alternative, with defaults).
const Option<RunOptions>& method_option();

/// --window: RunOptions::window, 0..kMaxWindow. A run's option, not a frame's (frame_window.h):
/// not in the table, whose options the Python module's one-frame Slider takes; its
/// slide_sequence takes this one (skinslide.h), the add-on's property is made from it.
const Option<RunOptions>& window_option();

/// --window-ends one-sided|cycle: RunOptions::window_ends, beside window_option and like it out of
/// the table.
const Option<RunOptions>& window_ends_option();

/// The window ends a word of --window-ends names. \throw Error(Usage) "unknown window end 'W'
/// (one-sided, cycle)".
WindowEnds window_ends_named(const std::string& word);
/// The word --window-ends names `ends` by.
std::string window_ends_name(WindowEnds ends);

}  // namespace skinslide
