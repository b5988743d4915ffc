// A whole run (README "Usage"): plan the frames and their outputs, set the bind up once, slide
// every frame on a pool of threads (parallel across frames only, so the bytes written never
// depend on the thread count), write the report. The command line's work without the command
// line: cli/main.cpp fills RunOptions from its options, prints the lines the run tells through
// RunEvents, and maps the run's errors to exit codes. Nothing here prints.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"
#include "pipeline/frame_plans.h"
#include "pipeline/log_lines.h"
#include "pipeline/run_options.h"

namespace skinslide {

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
  std::size_t frames = 0;         ///< frames --frames selected (written + failed)
  std::vector<Error> failures;    ///< keep_going: each failed frame's error (logged), frame order
  std::size_t not_converged = 0;  ///< frames written with a patch that did not converge
  /// Frames written whose --window mean costs them ten points of energy or more (their lines say
  /// "X% without the window": log_lines.h window_costly).
  std::size_t window_costly = 0;
};

/// Runs it all: plans the outputs (plan_frames / plan_rig_frames), reads the bind and the patch
/// and control files, sets the bind up, makes the output folder and the bind's dumps, then reads
/// (or poses), slides and writes the chosen frames on `threads` threads, each frame's dumps and
/// previews before its slid file; syncs the folders and writes the report. The outputs depend
/// on the inputs and options only, never on `threads` or the frames' order of completion.
/// An --output named like a cache (`shot.pc2`) with no --format is --format pc2 (FRAME files, a
/// clip; cache_format_named_by).
/// \throw Error: Usage for the plan's refusals and bad controls, Input for unreadable or
///        malformed inputs, Output when a folder or the report cannot be written; without
///        keep_going, the first failed frame's error (in frame order), after the frames started
///        have finished.
RunResult run(const RunOptions& options, const RunEvents& events = {});

}  // namespace skinslide
