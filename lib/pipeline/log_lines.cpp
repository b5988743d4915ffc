#include "pipeline/log_lines.h"

#include <algorithm>
#include <variant>

#include "core/number_format.h"

namespace skinslide {
namespace {

constexpr const char* kAtRest = "at rest (the bind to float32 precision), unchanged";

// A frame's line has figures when some patch slides and not every one is at rest.
bool has_figures(const BindSetup& setup, const std::vector<PatchFrameReport>& patches) {
  bool any_free = false, all_at_rest = true;
  for (size_t p = 0; p < setup.patches.size(); ++p)
    if (!setup.patches[p].skipped) {
      any_free = true;
      all_at_rest = all_at_rest && patches[p].at_rest;
    }
  return any_free && !all_at_rest;
}

}  // namespace

bool window_costly(const BindSetup& setup, const std::vector<PatchFrameReport>& patches) {
  if (patches.size() != setup.patches.size() || !has_figures(setup, patches)) return false;
  double before = 0, after = 0, own = 0;
  for (size_t p = 0; p < patches.size(); ++p) {
    const auto* r = std::get_if<ElasticReport>(&patches[p].method);
    if (!r || setup.patches[p].skipped) continue;
    before += r->energy_before;
    after += r->energy_after;
    own += r->energy_own;
  }
  return window_mean_costly(before, after, own);
}

std::vector<LogLine> frame_lines(const BindSetup& setup, const FrameResult& result,
                                 const std::string& frame_path, const std::string& out_path) {
  double max_slide = 0;
  for (const PatchFrameReport& p : result.patches) max_slide = std::max(max_slide, p.max_slide);
  const auto report = [&](size_t p) -> const MethodReport& { return result.patches[p].method; };
  // Figures where there is something to slide: a frame of skipped patches has no energy, and a
  // frame at rest comes back unchanged whatever is left of its float32 rounding.
  bool any_free = false;
  for (const Patch& p : setup.patches) any_free = any_free || !p.skipped;
  const std::string summary = !any_free ? "no free vertex: nothing slides"
                              : !has_figures(setup, result.patches)
                                  ? std::string(kAtRest)
                                  : frame_summary(setup.method, setup.patches, report,
                                                  ", max slide " + log_number(max_slide));
  std::vector<LogLine> lines;
  lines.push_back({LogLevel::Info, "skinslide: " + frame_path + ": " +
                                       counted(setup.patches.size(), "patch", "patches") + ", " +
                                       summary + " -> " + out_path});
  for (size_t p = 0; p < result.patches.size(); ++p) {
    const PatchFrameReport& r = result.patches[p];
    const std::string line = setup.patches[p].skipped ? "skipped (all vertices on loops)"
                             : r.at_rest              ? std::string(kAtRest)
                                                      : patch_summary(setup.method, p, r.method) +
                                               ", slide max " + log_number(r.max_slide) + " mean " +
                                               log_number(r.mean_slide);
    lines.push_back({LogLevel::Detail, "  patch " + std::to_string(p) + ": " + line});
  }
  return lines;
}

std::vector<LogLine> bind_lines(const RunOptions& o, const BindSetup& setup,
                                const SlideControls& controls) {
  std::vector<LogLine> lines;
  size_t sliding = 0;
  for (const Patch& p : setup.patches) sliding += p.free_vertices.size();
  if (o.no_slide)
    lines.push_back({LogLevel::Info, "skinslide: " + o.bind +
                                         ": --no-slide: frames are read, checked and written "
                                         "unchanged"});
  else
    lines.push_back(
        {LogLevel::Info,
         "skinslide: " + o.bind + ": " + counted(setup.patches.size(), "patch", "patches") + ", " +
             std::to_string(sliding) + " sliding vertices (" + method_label(setup.method) +
             (o.window > 0 ? ", window " + std::to_string(o.window) +
                                 (o.window_ends == WindowEnds::Cycle ? " around a loop" : "")
                           : std::string()) +
             ")"});
  const auto v = [&](const Patch& n, Index local) { return std::to_string(n.vertices[local]); };
  for (size_t p = 0; p < setup.patches.size(); ++p) {
    const Patch& n = setup.patches[p];
    lines.push_back({LogLevel::Detail, "  patch " + std::to_string(p) + ": " +
                                           std::to_string(n.faces.size()) + " faces, " +
                                           std::to_string(n.vertices.size()) + " vertices, " +
                                           std::to_string(n.loops.size()) + " loops, " +
                                           std::to_string(n.free_vertices.size()) + " free" +
                                           (n.skipped ? " (skipped)" : "") + ", bind net flips " +
                                           std::to_string(n.bind_net_flips)});
    if (n.skipped) continue;
    std::string loop = "    outer loop from vertex " + v(n, n.loops[n.outer_loop].front()) +
                       (n.outer_loop_chosen ? " (chosen)" : "");
    if (const auto c = square_corners(setup.method, p, n))  // the elastic chart is a disk: none
      loop += ", corners " + std::to_string(c->vertices[0]) + "," + std::to_string(c->vertices[1]) +
              "," + std::to_string(c->vertices[2]) + "," + std::to_string(c->vertices[3]) +
              (c->chosen ? " (chosen)" : "");
    lines.push_back({LogLevel::Detail, loop + ", " + std::to_string(n.pinned.size()) + " pinned"});
  }
  if (!controls.pins.empty())
    lines.push_back({LogLevel::Detail, "  " + std::to_string(controls.pins.size()) + " pins, " +
                                           std::to_string(setup.pins_ignored) +
                                           " of them on a boundary loop or outside every patch "
                                           "(ignored)"});
  return lines;
}

}  // namespace skinslide
