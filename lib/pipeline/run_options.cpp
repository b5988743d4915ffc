#include "pipeline/run_options.h"

namespace skinslide {
namespace {

WordOption<RunOptions> method_words() {
  WordOption<RunOptions> option;
  for_each_method([&](const std::string& name, const auto&) { option.words.push_back(name); });
  option.get = [](const RunOptions& o) { return method_name(o.slide); };
  option.set = [](RunOptions& o, const std::string& name) { o.slide = parse_method(name); };
  return option;
}

constexpr Words<WindowEnds, 2> kWindowEnds{
    "window end", {{{"one-sided", WindowEnds::OneSided}, {"cycle", WindowEnds::Cycle}}}};

}  // namespace

template <>
const OptionTable<RunOptions>& option_table<RunOptions>() {
  using O = RunOptions;
  static const OptionTable<O> table = {
      {"strength", "Multiplies every slide weight; the product is clamped to [0,1]",
       NumberOption<O, double>{&O::strength, 0.0, 1e6}},
      {"method",
       "elastic: the free vertices slide in a fixed chart of each patch towards the bind's edge "
       "lengths; paper: Yang & Zhang's bar nets, one linear solve a frame",
       method_words()},
  };
  return table;
}

MeshReadOptions mesh_read_options(const RunOptions& o) { return {o.mesh, o.allow_uri_outside}; }

const Option<RunOptions>& strength_option() { return option_table<RunOptions>()[0]; }
const Option<RunOptions>& method_option() { return option_table<RunOptions>()[1]; }

const Option<RunOptions>& window_option() {
  using O = RunOptions;
  static const Option<O> option = {
      "window",
      "Elastic: write each frame's slide as the mean of its own and its N neighbours' on each "
      "side in the sequence given (frame numbers; in the chart, weights N+1-|k|): smoother still "
      "in slow motion. A frame then depends on its neighbours: give a farm chunk the whole "
      "sequence and its range with --frames",
      NumberOption<O, int>{&O::window, 0, kMaxWindow}};
  return option;
}

WindowEnds window_ends_named(const std::string& word) { return kWindowEnds.value(word); }
std::string window_ends_name(WindowEnds ends) { return kWindowEnds.name(ends); }

const Option<RunOptions>& window_ends_option() {
  static const Option<RunOptions> option = {
      "window-ends",
      "With --window: one-sided: the first and last frames' windows end with the sequence; "
      "cycle: the sequence is a loop (a walk cycle, its last frame followed by its first), and "
      "the windows wrap around, so that the loop's seam is smoothed too",
      word_option(&RunOptions::window_ends, kWindowEnds)};
  return option;
}

}  // namespace skinslide
