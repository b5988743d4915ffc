#include "paper/paper_method.h"

#include <algorithm>
#include <utility>

#include "core/number_format.h"
#include "mesh/patch_figures.h"

namespace skinslide {
namespace {

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

}  // namespace

void set_up_patch(PaperMethod& method, std::size_t p, Patch& patch, const Positions3& points,
                  const CornerChoice& corners, bool spare_thread) {
  method.patches[p] = paper_setup(patch, points, method.options, corners, spare_thread);
}

std::optional<SquareCorners> square_corners(const PaperMethod& method, std::size_t p,
                                            const Patch& patch) {
  if (patch.skipped) return std::nullopt;
  SquareCorners c;
  for (int j = 0; j < 4; ++j) c.vertices[j] = patch.vertices[method.patches[p].corners[j]];
  c.chosen = method.patches[p].corners_chosen;
  return c;
}

PaperSlide slide_patch(const PaperMethod& method, std::size_t p, const Patch& patch,
                       const Positions3& points, const std::vector<double>& weight,
                       int id_image_size) {
  if (patch.skipped) return {};
  return paper_slide(method.patches[p], patch, points, weight, method.options, id_image_size);
}

std::string method_label(const PaperMethod& method) {
  return "method paper, density " + to_string(method.options.density) + ", holes " +
         to_string(method.options.holes);
}

Figures patch_figures(const PaperMethod& method, std::size_t p, const Patch& patch) {
  std::vector<long long> corners;
  if (const auto c = square_corners(method, p, patch))
    for (Index v : c->vertices) corners.push_back(v);
  Figures f = patch_counts(patch);
  for (Figure& loop : patch_loops(patch)) f.push_back(std::move(loop));
  f.push_back({"corners", corners});
  f.push_back({"corners_chosen", method.patches[p].corners_chosen});
  f.push_back({"skipped", patch.skipped});
  f.push_back({"bind_net_flips", static_cast<long long>(patch.bind_net_flips)});
  f.push_back({"frame_solver", solver_name(method.patches[p])});
  return f;
}

Figures report_figures(const PaperReport& r) {
  return {{"cg_iterations", static_cast<long long>(r.cg_iterations)},
          {"cg_residual", r.cg_residual},
          {"direct_solve", r.direct_solve},
          {"located_in_image", static_cast<long long>(r.located_in_image)},
          {"located_fallback", static_cast<long long>(r.located_fallback)},
          {"frame_net_flips", static_cast<long long>(r.frame_net_flips)},
          {"flips", static_cast<long long>(r.slid_flips)}};
}

void PaperTotals::add(const PaperReport& r) {
  cg_iterations += r.cg_iterations;
  direct_solves += r.direct_solve;
  fallbacks += r.located_fallback;
  frame_net_flips += r.frame_net_flips;
  flips += r.slid_flips;
}

Figures PaperTotals::figures() const {
  return {{"cg_iterations", cg_iterations},
          {"direct_solves", direct_solves},
          {"fallbacks", fallbacks},
          {"frame_net_flips", frame_net_flips},
          {"flips", flips}};
}

std::string frame_summary(const PaperMethod& method, const std::vector<Patch>& patches,
                          const std::function<const PaperReport&(std::size_t)>& report,
                          const std::string& max_slide) {
  std::vector<std::pair<FrameNetMethod, int>> used;
  int fallbacks = 0, flips = 0;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    const PaperReport& r = report(p);
    fallbacks += r.located_fallback;
    flips += r.slid_flips;
    if (patches[p].skipped) continue;
    const FrameNetMethod solver = method.patches[p].solver->method();
    auto it =
        std::find_if(used.begin(), used.end(), [&](const auto& u) { return u.first == solver; });
    if (it == used.end()) it = used.insert(used.end(), {solver, 0});
    it->second = std::max(it->second, r.cg_iterations);
  }
  std::string text;
  for (const auto& [solver, iterations] : used)
    text += (text.empty() ? "" : " + ") + solver_label(solver, iterations);
  return (used.empty() ? std::string("no frame net") : text) + max_slide + ", " +
         std::to_string(fallbacks) + " fallbacks, flips " + std::to_string(flips);
}

std::string patch_summary(const PaperMethod& method, std::size_t p, const PaperReport& r) {
  const FrameNetMethod solver = method.patches[p].solver->method();
  return solver_label(solver, r.cg_iterations) +
         (solver == FrameNetMethod::Cholesky ? "" : ", residual " + log_number(r.cg_residual)) +
         (r.direct_solve ? " (solved directly)" : "") + ", located " +
         std::to_string(r.located_in_image) + " + " + std::to_string(r.located_fallback) +
         " fallback, net flips " + std::to_string(r.frame_net_flips) + ", flips " +
         std::to_string(r.slid_flips);
}

}  // namespace skinslide
