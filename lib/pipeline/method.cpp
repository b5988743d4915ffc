#include "pipeline/method.h"

#include <algorithm>
#include <utility>

#include "core/number_format.h"

namespace skinslide {
namespace {

using Long = long long;

Long count(std::size_t n) { return static_cast<Long>(n); }

// The report's figures that both methods give a patch, in three runs around their own.
Figures patch_counts(const Patch& p) {
  return {{"faces", count(p.faces.size())},
          {"vertices", count(p.vertices.size())},
          {"free", count(p.free_vertices.size())},
          {"pinned", count(p.pinned.size())}};
}

Figures patch_loops(const Patch& p) {
  return {{"loops", count(p.loops.size())},
          {"outer_loop_start", Long{p.vertices[p.loops[p.outer_loop].front()]}},
          {"outer_loop_chosen", p.outer_loop_chosen}};
}

void append(Figures& to, Figures more) {
  for (Figure& f : more) to.push_back(std::move(f));
}

// ---- The elastic method -----------------------------------------------------------------------

void set_up(ElasticMethod& m, std::size_t p, Patch& patch, const Positions3& points,
            const std::vector<double>& weight, const CornerChoice&, bool) {
  m.patches[p] = elastic_patch_setup(patch, points, weight);
}

std::optional<SquareCorners> corners_of(const ElasticMethod&, std::size_t, const Patch&) {
  return std::nullopt;  // the chart is a disk
}

MethodSlide slide(const ElasticMethod& m, std::size_t p, const Patch& patch,
                  const Positions3& points, const std::vector<double>& weight, int image_size) {
  if (patch.skipped) return {PatchSlide{}, ElasticReport{}};
  ElasticSlide s = elastic_slide(*m.patches[p], patch, points, weight, m.options, image_size);
  return {std::move(s.slid), std::move(s.report)};
}

std::string label(const ElasticMethod&) { return "method elastic"; }

Figures options_of(const ElasticMethod& m) {
  return {{"method", std::string("elastic")},
          {"rotation_fits", Long{m.options.rotation_fits}},
          {"max_iterations", Long{m.options.max_iterations}},
          {"tolerance", m.options.tolerance}};
}

Figures patch_of(const ElasticMethod& m, std::size_t p, const Patch& patch) {
  const ElasticSetup* e = m.patches[p].get();
  Figures f = patch_counts(patch);
  f.push_back({"moving", count(e ? e->movable.size() : 0)});
  append(f, patch_loops(patch));
  f.push_back({"skipped", patch.skipped});
  f.push_back({"chart_weights", std::string(!e                         ? "none"
                                            : e->chart.uniform_weights ? "uniform"
                                                                       : "mean value")});
  return f;
}

Figures figures_of(const ElasticReport& r) {
  return {{"energy_before", r.energy_before},
          {"energy_after", r.energy_after},
          {"iterations", Long{r.iterations}},
          {"solves", Long{r.solves}},
          {"solve_iterations", Long{r.solve_iterations}},
          {"stop", r.stop.empty() ? std::string("skipped") : r.stop},
          {"held", Long{r.held}},
          {"flips", Long{r.slid_flips}}};
}

Figures totals_of(const ElasticMethod&, const std::vector<MethodReport>& reports) {
  Long iterations = 0, held = 0, flips = 0;
  for (const MethodReport& report : reports) {
    const ElasticReport& r = std::get<ElasticReport>(report);
    iterations += r.iterations;
    held += r.held;
    flips += r.slid_flips;
  }
  return {{"iterations", iterations}, {"held", held}, {"flips", flips}};
}

// Most steps, and the energy left as a share of the frame's.
std::string summary_of(const ElasticMethod&, const std::vector<Patch>& patches,
                       const std::vector<MethodReport>& reports, const std::string& max_slide) {
  int iterations = 0, flips = 0;
  double before = 0, after = 0;
  for (std::size_t p = 0; p < reports.size(); ++p) {
    if (patches[p].skipped) continue;
    const ElasticReport& r = std::get<ElasticReport>(reports[p]);
    iterations = std::max(iterations, r.iterations);
    flips += r.slid_flips;
    before += r.energy_before;
    after += r.energy_after;
  }
  return "elastic " + std::to_string(iterations) + " it, energy left " +
         (before > 0 ? log_number(100 * after / before) + "%" : std::string("0")) + ", flips " +
         std::to_string(flips) + max_slide;
}

std::string patch_line(const ElasticMethod&, std::size_t, const ElasticReport& r) {
  return "elastic " + std::to_string(r.iterations) + " it (" + r.stop + "), energy " +
         log_number(r.energy_before) + " -> " + log_number(r.energy_after) + ", held " +
         std::to_string(r.held) + ", flips " + std::to_string(r.slid_flips);
}

// ---- The paper's method -----------------------------------------------------------------------

void set_up(PaperMethod& m, std::size_t p, Patch& patch, const Positions3& points,
            const std::vector<double>&, const CornerChoice& corners, bool spare_thread) {
  m.patches[p] = paper_setup(patch, points, m.options, corners, spare_thread);
}

std::optional<SquareCorners> corners_of(const PaperMethod& m, std::size_t p, const Patch& patch) {
  if (patch.skipped) return std::nullopt;
  SquareCorners c;
  for (int j = 0; j < 4; ++j) c.vertices[j] = patch.vertices[m.patches[p].corners[j]];
  c.chosen = m.patches[p].corners_chosen;
  return c;
}

MethodSlide slide(const PaperMethod& m, std::size_t p, const Patch& patch, const Positions3& points,
                  const std::vector<double>& weight, int image_size) {
  if (patch.skipped) return {PatchSlide{}, PaperReport{}};
  PaperSlide s = paper_slide(m.patches[p], patch, points, weight, m.options, image_size);
  return {std::move(s.slid), s.report};
}

std::string label(const PaperMethod& m) {
  return "method paper, density " + to_string(m.options.density) + ", holes " +
         to_string(m.options.holes);
}

Figures options_of(const PaperMethod& m) {
  const PaperOptions& o = m.options;
  return {{"method", std::string("paper")},
          {"density", to_string(o.density)},
          {"holes", to_string(o.holes)},
          {"q_floor", o.q_floor},
          {"frame_solver", to_string(o.frame_solver)},
          {"cg_tolerance", o.cg_tolerance},
          {"cg_max_iterations", Long{o.cg_max_iterations}},
          {"locate", to_string(o.locate)},
          {"lookup_size", Long{o.lookup_size}}};
}

// What --frame-solver auto chose for the patch, in the option's words.
std::string solver_name(const PaperSetup& setup) {
  if (!setup.solver) return "none";
  switch (setup.solver->method()) {
    case FrameNetMethod::Cholesky:
      return "cholesky";
    case FrameNetMethod::Cg:
      return "cg";
    case FrameNetMethod::Multigrid:
      return "multigrid";
  }
  return "?";
}

Figures patch_of(const PaperMethod& m, std::size_t p, const Patch& patch) {
  std::vector<Long> corners;
  if (const auto c = corners_of(m, p, patch))
    for (Index v : c->vertices) corners.push_back(v);
  Figures f = patch_counts(patch);
  append(f, patch_loops(patch));
  f.push_back({"corners", corners});
  f.push_back({"corners_chosen", m.patches[p].corners_chosen});
  f.push_back({"skipped", patch.skipped});
  f.push_back({"bind_net_flips", Long{patch.bind_net_flips}});
  f.push_back({"frame_solver", solver_name(m.patches[p])});
  return f;
}

Figures figures_of(const PaperReport& r) {
  return {{"cg_iterations", Long{r.cg_iterations}},
          {"cg_residual", r.cg_residual},
          {"direct_solve", r.direct_solve},
          {"located_in_image", Long{r.located_in_image}},
          {"located_fallback", Long{r.located_fallback}},
          {"frame_net_flips", Long{r.frame_net_flips}}};
}

Figures totals_of(const PaperMethod&, const std::vector<MethodReport>& reports) {
  Long iterations = 0, direct = 0, fallbacks = 0, flips = 0;
  for (const MethodReport& report : reports) {
    const PaperReport& r = std::get<PaperReport>(report);
    iterations += r.cg_iterations;
    direct += r.direct_solve;
    fallbacks += r.located_fallback;
    flips += r.frame_net_flips;
  }
  return {{"cg_iterations", iterations},
          {"direct_solves", direct},
          {"fallbacks", fallbacks},
          {"frame_net_flips", flips}};
}

std::string solver_label(FrameNetMethod method, int iterations) {
  switch (method) {
    case FrameNetMethod::Cholesky:
      return "Cholesky";
    case FrameNetMethod::Cg:
      return "CG " + std::to_string(iterations) + " it";
    case FrameNetMethod::Multigrid:
      return "multigrid " + std::to_string(iterations) + " it";
  }
  return "?";
}

// The frame's solvers, each once, in patch order, an iterative one with its most iterations;
// then the fallbacks.
std::string summary_of(const PaperMethod& m, const std::vector<Patch>& patches,
                       const std::vector<MethodReport>& reports, const std::string& max_slide) {
  std::vector<std::pair<FrameNetMethod, int>> used;
  int fallbacks = 0;
  for (std::size_t p = 0; p < reports.size(); ++p) {
    const PaperReport& r = std::get<PaperReport>(reports[p]);
    fallbacks += r.located_fallback;
    if (patches[p].skipped) continue;
    const FrameNetMethod method = m.patches[p].solver->method();
    auto it =
        std::find_if(used.begin(), used.end(), [&](const auto& u) { return u.first == method; });
    if (it == used.end()) it = used.insert(used.end(), {method, 0});
    it->second = std::max(it->second, r.cg_iterations);
  }
  std::string text;
  for (const auto& [method, iterations] : used)
    text += (text.empty() ? "" : " + ") + solver_label(method, iterations);
  return (used.empty() ? std::string("no frame net") : text) + max_slide + ", " +
         std::to_string(fallbacks) + " fallbacks";
}

std::string patch_line(const PaperMethod& m, std::size_t p, const PaperReport& r) {
  const FrameNetMethod method = m.patches[p].solver->method();
  return solver_label(method, r.cg_iterations) +
         (method == FrameNetMethod::Cholesky ? "" : ", residual " + log_number(r.cg_residual)) +
         (r.direct_solve ? " (solved directly)" : "") + ", located " +
         std::to_string(r.located_in_image) + " + " + std::to_string(r.located_fallback) +
         " fallback, net flips " + std::to_string(r.frame_net_flips);
}

}  // namespace

// ---- The choice, visited ----------------------------------------------------------------------

MethodSetup method_setup(const SlideOptions& options, std::size_t patch_count) {
  return std::visit(
      [&](const auto& o) -> MethodSetup {
        using Options = std::decay_t<decltype(o)>;
        if constexpr (std::is_same_v<Options, ElasticOptions>)
          return ElasticMethod{o, std::vector<std::shared_ptr<const ElasticSetup>>(patch_count)};
        else
          return PaperMethod{o, std::vector<PaperSetup>(patch_count)};
      },
      options);
}

SlideOptions method_options(const MethodSetup& method) {
  return std::visit([](const auto& m) -> SlideOptions { return m.options; }, method);
}

void set_up_patch(MethodSetup& method, std::size_t p, Patch& patch, const Positions3& points,
                  const std::vector<double>& weight, const CornerChoice& corners,
                  bool spare_thread) {
  std::visit([&](auto& m) { set_up(m, p, patch, points, weight, corners, spare_thread); }, method);
}

std::optional<SquareCorners> square_corners(const MethodSetup& method, std::size_t p,
                                            const Patch& patch) {
  return std::visit([&](const auto& m) { return corners_of(m, p, patch); }, method);
}

MethodSlide slide_patch(const MethodSetup& method, std::size_t p, const Patch& patch,
                        const Positions3& points, const std::vector<double>& weight,
                        int id_image_size) {
  return std::visit(
      [&](const auto& m) { return slide(m, p, patch, points, weight, id_image_size); }, method);
}

std::string method_label(const MethodSetup& method) {
  return std::visit([](const auto& m) { return label(m); }, method);
}

Figures option_figures(const MethodSetup& method) {
  return std::visit([](const auto& m) { return options_of(m); }, method);
}

Figures patch_figures(const MethodSetup& method, std::size_t p, const Patch& patch) {
  return std::visit([&](const auto& m) { return patch_of(m, p, patch); }, method);
}

Figures report_figures(const MethodReport& report) {
  return std::visit([](const auto& r) { return figures_of(r); }, report);
}

Figures total_figures(const MethodSetup& method, const std::vector<MethodReport>& reports) {
  return std::visit([&](const auto& m) { return totals_of(m, reports); }, method);
}

std::string frame_summary(const MethodSetup& method, const std::vector<Patch>& patches,
                          const std::vector<MethodReport>& reports, const std::string& max_slide) {
  return std::visit([&](const auto& m) { return summary_of(m, patches, reports, max_slide); },
                    method);
}

std::string patch_summary(const MethodSetup& method, std::size_t p, const MethodReport& report) {
  return std::visit(
      [&](const auto& m) {
        using Report = std::conditional_t<std::is_same_v<std::decay_t<decltype(m)>, ElasticMethod>,
                                          ElasticReport, PaperReport>;
        return patch_line(m, p, std::get<Report>(report));
      },
      method);
}

}  // namespace skinslide
