// The run report (`--report FILE.json`): what happened to every patch in every frame, as JSON
// that diffs. Keys in a fixed order, numbers as the shortest text that reads back to the same
// double (std::to_chars), frames in the order given. Timings are the only numbers that change
// from run to run; they sit in one top-level "timings" object (omitted on request) so a diff can
// drop it.
#pragma once

#include <string>
#include <vector>

#include "pipeline/bind_setup.h"
#include "pipeline/run_options.h"
#include "pipeline/slide_frame.h"

namespace skinslide {

/// One frame of the run, in the order of the command line.
struct ReportFrame {
  std::string path;                       ///< the frame's file
  std::string output;                     ///< where the slid frame was written
  std::vector<PatchFrameReport> patches;  ///< parallel to BindSetup::patches (nets not needed)
  double read_seconds = 0;                ///< reading and checking the frame (posing a rig frame)
  double write_seconds = 0;               ///< writing the slid frame
};

/// What the report says about a run besides the frames.
struct RunReport {
  std::string bind;  ///< the bind's file
  std::vector<std::string> patch_files;
  std::string weights;  ///< where the slide weights came from; empty = none
  double strength = 1;
  int window = 0;  ///< --window (elastic): its reach N, in "options" after the method's
  WindowEnds window_ends = WindowEnds::OneSided;  ///< --window-ends, after window
  std::string pins;                               ///< the pin file; empty = none
  Index pins_requested = 0;                       ///< distinct ids in the pin file
  std::vector<ReportFrame> frames;
  bool timings = true;      ///< write the "timings" object
  double bind_seconds = 0;  ///< reading the bind and patch files, building the set-up
  double wall_seconds = 0;  ///< the whole run
};

/// The report as JSON text (UTF-8, 2-space indent, final newline). Layout:
/// { "skinslide": version, "bind", "patch_files", "options": {method, then its tunables
///   (method.h option_figures), then, for the elastic method, window and window_ends}, "controls":
///   {weights, strength, pins, pins_requested, pins_ignored}, "patches": [per patch: faces,
///   vertices, free, pinned, loops, outer_loop_start, outer_loop_chosen, skipped and the method's
///   figures, in the order patch_figures gives them], "frames": [{path, output, patches: [{the
///   method's figures (report_figures), moved, max_slide, mean_slide, spread_frame,
///   spread_slid}]}], "totals": {frames, moved, the method's sums (total_figures), max_slide, with
///   --window window_costly (frames whose window's mean costs them ten points: log_lines.h)},
///   "timings": {seconds per stage summed over frames: bind_setup, read, solve, locate, transfer,
///   write; wall} }
/// Skipped patches report zeros. Vertex ids are mesh ids.
std::string report_json(const BindSetup& setup, const RunReport& run);

/// The report's record of one frame: its figures, not its nets (`patches` are moved in, their
/// frame nets and ID images dropped).
void record_frame(ReportFrame& record, const std::string& source, const std::string& out_path,
                  double read_seconds, double write_seconds, std::vector<PatchFrameReport> patches);

/// Writes the report (`o.report`) last and atomically, then syncs its folder: the bind and patch
/// files from `o`, the frames `report` recorded (under --keep-going those written).
/// \throw Error(Output) when it cannot be written.
void write_run_report(const RunOptions& o, const BindSetup& setup, double wall_seconds,
                      RunReport& report);

}  // namespace skinslide
