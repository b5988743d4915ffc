// A whole run (README "Usage"): plan the frames and their outputs, set the bind up once, slide
// every frame on a pool of threads (parallel across frames only, so the bytes written never
// depend on the thread count), write the report. The command line's work without the command
// line: cli/main.cpp fills RunOptions from its options, prints the lines the run tells through
// RunEvents, and maps the run's errors to exit codes. Nothing here prints.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/types.h"
#include "io/point_cache.h"
#include "locate/id_raster.h"
#include "pipeline/dumps.h"
#include "pipeline/options.h"
#include "pipeline/rig_frames.h"

namespace skinslide {

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
  // Outputs
  std::string output = "slid";      ///< folder of the slid frames, created if missing
  std::string dump_dir;             ///< --dump: EXR images of the nets; empty = none
  std::string preview_dir;          ///< --preview: PNG pictures of the nets; empty = none
  int preview_size = kPreviewSize;  ///< side of the preview PNGs, pixels
  int lookup_size = kLookupSize;    ///< side of the dumps' ID images, pixels (--lookup-size)
  std::string report;               ///< --report JSON file; empty = none
  bool report_timings = true;       ///< false: --report-no-timings
  // Method
  SlideOptions slide;  ///< the method and its options
  // Controls (README "Controls"), read after the bind: their ids are checked against it.
  std::string weights;                      ///< --weights file; empty = none
  std::string weights_from_obj_color;       ///< "r", "g" or "b" of the OBJ bind; empty = none
  std::string weights_from_gltf_attribute;  ///< a vertex attribute of the glTF bind; empty = none
  double strength = 1;                      ///< multiplies every weight
  std::string pin;                          ///< --pin file; empty = none
  std::vector<std::string> corners;         ///< --corners as given, each "a,b,c,d"
  std::vector<Index> outer_loop_vertices;   ///< --outer-loop-vertex, one per patch
  // Run
  unsigned threads = 0;      ///< frames (and patches) processed at once; 0 = usable_cores()
  std::string frame_ranges;  ///< --frames (pipeline/frame_ranges.h); empty = every frame
  bool keep_going = false;   ///< write every good frame and name every bad one
  bool no_slide = false;     ///< read, check and write every frame unchanged (not with `rig`)
};

/// The frames a run slides and where each goes; made before any frame is read.
struct FramePlan {
  std::vector<std::string> outputs;  ///< per frame in list order, OUTPUT/<frame's file name>
  std::vector<std::size_t> chosen;   ///< the frames --frames selects: indices, ascending
  /// The point cache every chosen frame goes to (each frame's output names it too); empty when
  /// each frame has a file of its own.
  std::string cache;
};

/// The plan of a run of FRAME files: OUTPUT/<file name> per frame, and the frames whose file
/// names carry a number --frames names (`arm.0042.obj` -> 42; pipeline/frame_ranges.h). Reads
/// no mesh; looks at the file system only to tell whether two paths are one file.
/// \throw Error(Usage) for: a malformed --frames; two frames with one file name; an output that
///        is an input (BIND, FRAME, --patch, --weights, --pin); a --report that is an input or a
///        frame's output; with --frames, a frame without a number or a selection of none.
FramePlan plan_frames(const RunOptions& options);

/// The plan of a --animation run: OUTPUT/<name>.<format> for each of `names`
/// (RigClip::names, "<character stem>.<frame>"), and those --frames selects by frame number;
/// with a cache format, one cache of the chosen frames (OUTPUT/<character stem>.pc2, or a chunk
/// named by its first and last frame: cache_frames.h cache_output_path).
/// \throw Error(Usage) for: a malformed --frames; an output that is BIND or a --patch file; a
///        --frames selecting none, or, for a cache, frames with gaps between them.
FramePlan plan_rig_frames(const RunOptions& options, const std::vector<std::string>& names);

/// The plan of a run whose FRAME is a point cache (`cache`, whose samples have the frame names
/// `names`: cache_frames.h): the samples --frames selects by frame number, and either the cache
/// they are written to (the FRAME's format: OUTPUT/<cache's file name>, or a chunk named by its
/// first and last frame) or, with --format obj or glb, OUTPUT/<name>.<format> a sample.
/// \throw Error(Usage) for: a malformed --frames or one selecting none; a cache chunk with gaps;
///        --format naming the other cache format; per-frame files for two samples of one frame;
///        an output or --report that is an input, or a chunk in the input's folder (the join
///        of the chunks would replace the input); a --report that is an output.
FramePlan plan_cache_frames(const RunOptions& options, const CacheHeader& cache,
                            const std::vector<std::string>& names);

/// How much a log line tells: cli/ prints Info unless -q, Detail only with -v, Error always.
enum class LogLevel { Info, Detail, Error };

/// One line for the log, without its newline: "skinslide: ..." or an indented detail.
struct LogLine {
  LogLevel level = LogLevel::Info;
  std::string text;
};

/// What a run tells as it goes. Every member may be empty (not told).
struct RunEvents {
  /// A line about the run as a whole (the bind and its patches, the frames' failures under
  /// keep_going), in order, on the thread that called run().
  std::function<void(const LogLine&)> log;
  /// The frames are about to be slid: how many --frames selects. Once, before any frame_done.
  std::function<void(std::size_t count)> frames_begin;
  /// Chosen frame `j` (0-based, in list order) is finished, with its lines: one Info line, and
  /// a Detail line per patch. A frame that failed under keep_going is told with no lines; one
  /// that failed otherwise is not told. Called from the worker threads, concurrently and in any
  /// order: it must be thread-safe.
  std::function<void(std::size_t j, std::vector<LogLine> lines)> frame_done;
  /// Every frame is finished (or stopped); before failures are logged and the report written.
  std::function<void()> frames_end;
};

/// What a finished run did.
struct RunResult {
  std::size_t frames = 0;       ///< frames --frames selected (written + failed)
  std::vector<Error> failures;  ///< keep_going: each failed frame's error (logged), frame order
};

/// Runs it all: plans the outputs (plan_frames / plan_rig_frames), reads the bind and the patch
/// and control files, sets the bind up, makes the output folder and the bind's dumps, then reads
/// (or poses), slides and writes the chosen frames on `threads` threads, each frame's dumps and
/// previews before its slid file; syncs the folders and writes the report. The outputs depend
/// on the inputs and options only, never on `threads` or the frames' order of completion.
/// \throw Error: Usage for the plan's refusals and bad controls, Input for unreadable or
///        malformed inputs, Output when a folder or the report cannot be written; without
///        keep_going, the first failed frame's error (in frame order), after the frames started
///        have finished.
RunResult run(const RunOptions& options, const RunEvents& events = {});

}  // namespace skinslide
