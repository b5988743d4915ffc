#include "elastic/elastic_method.h"

#include <algorithm>

#include "core/number_format.h"
#include "mesh/patch_figures.h"

namespace skinslide {

void set_up_patch(ElasticMethod& method, std::size_t p, Patch& patch, const Positions3& points,
                  const std::vector<double>& weight) {
  method.patches[p] = elastic_patch_setup(patch, points, weight, method.options.blend);
}

ElasticSlide slide_patch(const ElasticMethod& method, std::size_t p, const Patch& patch,
                         const Positions3& points, const std::vector<double>& weight,
                         int id_image_size) {
  if (patch.skipped) return {};
  return elastic_slide(*method.patches[p], patch, points, weight, method.options, id_image_size);
}

std::string method_label(const ElasticMethod&) { return "method elastic"; }

Figures patch_figures(const ElasticMethod& method, std::size_t p, const Patch& patch) {
  const ElasticSetup* e = method.patches[p].get();
  Figures f = patch_counts(patch);
  f.push_back({"moving", static_cast<long long>(e ? e->movable.size() : 0)});
  for (Figure& loop : patch_loops(patch)) f.push_back(std::move(loop));
  f.push_back({"skipped", patch.skipped});
  f.push_back({"chart_weights", std::string(!e                         ? "none"
                                            : e->chart.uniform_weights ? "uniform"
                                                                       : "mean value")});
  return f;
}

bool converged(const ElasticReport& r) {
  return r.stop.empty() || r.stop == stop_name(ElasticStop::Converged) ||
         r.stop == stop_name(ElasticStop::AtRest);
}

double first_order_share(const ElasticReport& r) {
  return r.energy_before > 0 ? r.gain_left / r.energy_before : 0.0;
}

Figures report_figures(const ElasticReport& r) {
  return {{"energy_before", r.energy_before},
          {"energy_after", r.energy_after},
          {"iterations", static_cast<long long>(r.iterations)},
          {"solves", static_cast<long long>(r.solves)},
          {"solve_iterations", static_cast<long long>(r.solve_iterations)},
          {"escalations", static_cast<long long>(r.escalations)},
          {"stop", r.stop.empty() ? std::string("skipped") : r.stop},
          {"converged", converged(r)},
          {"first_order_gain", r.gain_left},
          {"first_order_share", first_order_share(r)},
          {"held", static_cast<long long>(r.held)},
          {"flips", static_cast<long long>(r.slid_flips)},
          {"window_returned", static_cast<long long>(r.window_returned)}};
}

void ElasticTotals::add(const ElasticReport& r) {
  iterations += r.iterations;
  held += r.held;
  flips += r.slid_flips;
  window_returned += r.window_returned;
  not_converged += converged(r) ? 0 : 1;
}

Figures ElasticTotals::figures() const {
  return {{"iterations", iterations},
          {"held", held},
          {"flips", flips},
          {"window_returned", window_returned},
          {"not_converged", not_converged}};
}

std::string convergence_text(const ElasticReport& r) {
  if (r.stop.empty() || r.stop == stop_name(ElasticStop::AtRest)) return r.stop;
  return r.stop + ", first-order gain left " + log_number(100 * first_order_share(r)) + "%";
}

// A window's mean is told on the frame's line when it keeps more of the frame's energy than its
// own slide by this share of the frame's energy: ten points of "energy left" (lib/elastic/README.md
// rule 12), above what a window over one motion costs and below what one mixing separate poses
// does (tests/bench/elastic.md "Figures behind the code's constants").
constexpr double kWindowCostTold = 0.1;

bool window_mean_costly(double before, double after, double own) {
  return before > 0 && after - own > kWindowCostTold * before;
}

std::string frame_summary(const std::vector<Patch>& patches,
                          const std::function<const ElasticReport&(std::size_t)>& report,
                          const std::string& max_slide) {
  int iterations = 0, flips = 0, returned = 0;
  double before = 0, after = 0, own = 0;
  std::string unconverged;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    if (patches[p].skipped) continue;
    const ElasticReport& r = report(p);
    iterations = std::max(iterations, r.iterations);
    flips += r.slid_flips;
    returned += r.window_returned;
    before += r.energy_before;
    after += r.energy_after;
    own += r.energy_own;
    if (!converged(r))
      unconverged += (unconverged.empty() ? ", not converged: patch " : ", patch ") +
                     std::to_string(p) + " (" + convergence_text(r) + ")";
  }
  // --window's mean given way to a frame's own slide (rule 12) is told, not only counted.
  const std::string window_text =
      returned > 0 ? ", " + std::to_string(returned) + " vertices off the window's mean"
                   : std::string();
  // A window whose mean keeps much more energy than the frame's own slide averages frames too far
  // apart to share one (a fast motion, a sequence's end, separate poses): said, not left to the
  // energy figure alone.
  const std::string window_cost =
      window_mean_costly(before, after, own)
          ? ", " + log_number(100 * own / before) +
                "% without the window (its frames differ too much to share a mean)"
          : std::string();
  return "elastic " + std::to_string(iterations) + " it, energy left " +
         (before > 0 ? log_number(100 * after / before) + "%" : std::string("0")) + ", flips " +
         std::to_string(flips) + max_slide + window_text + window_cost + unconverged;
}

std::string patch_summary(const ElasticReport& r) {
  return "elastic " + std::to_string(r.iterations) + " it (" + convergence_text(r) + "), energy " +
         log_number(r.energy_before) + " -> " + log_number(r.energy_after) + ", held " +
         std::to_string(r.held) + ", flips " + std::to_string(r.slid_flips);
}

}  // namespace skinslide
