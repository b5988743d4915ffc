// Where every frame of a run goes, planned before any frame is read (README "Usage", "Farm"): a
// run of FRAME files, of a rigged character's clip, of a point cache's samples; the frames
// --frames selects; the refusals that keep a run from writing over what it reads.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "io/point_cache.h"
#include "pipeline/frame_ranges.h"
#include "pipeline/run_options.h"

namespace skinslide {

/// The frames a run slides and where each goes; made before any frame is read.
struct FramePlan {
  std::vector<std::string> outputs;  ///< per frame in list order, OUTPUT/<frame's file name>
  std::vector<std::size_t> chosen;   ///< the frames --frames selects: indices, ascending
  /// The point cache every chosen frame goes to (each frame's output names it too); empty when
  /// each frame has a file of its own.
  std::string cache;
  /// FRAME files written as one cache: the whole sequence's header (frame numbers, or MDD
  /// times, from the files' names: plan_frames).
  CacheHeader whole;
  std::string folder;  ///< the folder every output is in, made if missing
};

/// Where a run writing one point cache puts it: an --output ending in the cache's extension
/// (`shot.pc2`) is the cache itself, in its folder; any other --output is the folder of
/// `<stem><extension>`.
struct CacheTarget {
  std::string folder;
  std::string stem;
};
CacheTarget cache_target(const std::string& output, const std::string& stem,
                         const std::string& extension);

/// The plan of a run of FRAME files: OUTPUT/<file name> per frame, and the frames whose file
/// names carry a number --frames names (`arm.0042.obj` -> 42; pipeline/frame_ranges.h). With
/// --format pc2 or mdd, one cache of the chosen frames instead (cache_target; the stem is the
/// frames' name without its number, `arm` for arm.0001.obj): PC2 frames are the files' numbers,
/// which must rise by one step (startFrame the first, sampleRate the step; files without numbers
/// count from 0); MDD times are those numbers over --fps. Reads no mesh; looks at the file
/// system only to tell whether two paths are one file (io/file_key.h: a stat a path, O(n)).
/// \throw Error(Input) "PATH: cannot read: REASON" for an input the system cannot look at (a
///        folder on its way the user may not enter), Error(Output) "cannot write" for an output;
///        Error(Usage) for: an --output named like a mesh file (`-o shot.obj`: it is a folder); a
///        BIND named as a member of the FRAME sequence (frame_sequence: the bind forgotten, a frame
///        taken for it) unless --bind-is-frame; a malformed --frames; two frames with one file
///        name; an output that is an input (BIND, FRAME, --patch,
///        --weights, --pin); a --report that is an input or a frame's output; with --frames, a
///        frame without a number or a selection of none; for a cache: numbers that do not rise
///        by one step (PC2) or at all (MDD), some files numbered and some not, MDD without
///        --fps, times one float32, a chunk with gaps.
FramePlan plan_frames(const RunOptions& options);

/// The plan of a --animation run: OUTPUT/<name>.<format> for each of `names`
/// (RigClip::names, "<character stem>.<frame>"), and those --frames selects by frame number;
/// with a cache format, one cache of the chosen frames (OUTPUT/<character stem>.pc2, or a chunk
/// named by its first and last frame: cache_frames.h cache_output_path).
/// \throw Error(Usage) for: an --output named like a mesh file; a malformed --frames; an output
///        that is BIND or a --patch file; a --frames selecting none, or, for a cache, frames with
///        gaps between them.
FramePlan plan_rig_frames(const RunOptions& options, const std::vector<std::string>& names);

/// The plan of a run whose FRAME is a point cache (`cache`, whose samples have the frame names
/// `names`: cache_frames.h): the samples --frames selects by frame number, and either the cache
/// they are written to (the FRAME's format: OUTPUT/<cache's file name>, or a chunk named by its
/// first and last frame) or, with --format obj or glb, OUTPUT/<name>.<format> a sample.
/// \throw Error(Usage) for: an --output named like a mesh file; a malformed --frames or one
///        selecting none; a cache chunk with gaps;
///        --format naming the other cache format; per-frame files for two samples of one frame;
///        an output or --report that is an input, or a chunk in the input's folder (the join
///        of the chunks would replace the input); a --report that is an output.
FramePlan plan_cache_frames(const RunOptions& options, const CacheHeader& cache,
                            const std::vector<std::string>& names);

/// The cache format an --output names by its extension ("pc2" for `shot.pc2`, "mdd"), else "":
/// a run of FRAME files or of a clip given no --format writes that cache (README "Point
/// caches"), as with --format.
std::string cache_format_named_by(const std::string& output);

/// The run's --frames, parsed; empty = every frame. \throw Error(Usage) when malformed.
std::vector<FrameRange> frame_ranges(const RunOptions& options);

}  // namespace skinslide
