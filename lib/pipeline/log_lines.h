// What a run tells as it goes, as lines for the log (README "Usage"): the bind's and each frame's,
// a summary and per-patch details. The library never prints: cli/ prints them, the Python module
// does not ask for them.
#pragma once

#include <string>
#include <vector>

#include "pipeline/bind_setup.h"
#include "pipeline/run_options.h"
#include "pipeline/slide_frame.h"

namespace skinslide {

/// How much a log line tells: cli/ prints Info unless -q, Detail only with -v, Error always.
/// Info: told unless -q; Detail: with -v; Warning: always, as a run's result may not be what was
/// meant (a farm task's windows cut short); Error: always.
enum class LogLevel { Info, Detail, Error, Warning };

/// One line for the log, without its newline: "skinslide: ..." or an indented detail.
struct LogLine {
  LogLevel level = LogLevel::Info;
  std::string text;
};

/// A slid frame's lines: a summary (Info), then a line per patch (Detail).
std::vector<LogLine> frame_lines(const BindSetup& setup, const FrameResult& result,
                                 const std::string& frame_path, const std::string& out_path);

/// True when --window's mean costs the frame ten points of its energy or more: its line says
/// "X% without the window" (elastic/elastic_method.h frame_summary, its window_mean_costly), on
/// the same sums over the frame's patches (`patches`, parallel to setup.patches), and a frame of
/// skipped patches or at rest has no such line. Never without a window (its mean is the frame's
/// own slide) nor with the paper method.
bool window_costly(const BindSetup& setup, const std::vector<PatchFrameReport>& patches);

/// The bind's lines: a summary (Info), then per patch its nets and loops (Detail), and the pins.
std::vector<LogLine> bind_lines(const RunOptions& o, const BindSetup& setup,
                                const SlideControls& controls);

}  // namespace skinslide
