// The elastic method as a run holds and tells it: every patch's set-up, and the method's figures
// for the report and its log text. pipeline/method.h dispatches to these and to
// paper/paper_method.h, which has the same shape.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/figures.h"
#include "core/types.h"
#include "elastic/elastic_slide.h"
#include "mesh/patch.h"

namespace skinslide {

/// The elastic method's bind-time data: its options and every patch's set-up.
struct ElasticMethod {
  ElasticOptions options;
  /// Parallel to BindSetup::patches; null for a skipped patch.
  std::vector<std::shared_ptr<const ElasticSetup>> patches;
};

/// Sets patch `p` up (elastic_patch_setup) into its slot of `method`.
void set_up_patch(ElasticMethod& method, std::size_t p, Patch& patch, const Positions3& points,
                  const std::vector<double>& weight);

/// Slides patch `p` in one frame (nothing moves in a skipped patch). Arguments as elastic_slide.
ElasticSlide slide_patch(const ElasticMethod& method, std::size_t p, const Patch& patch,
                         const Positions3& points, const std::vector<double>& weight,
                         int id_image_size);

/// For the bind's log line: "method elastic".
std::string method_label(const ElasticMethod& method);

/// The report's entry for patch `p` at bind: counts, moving, loops, skipped, chart_weights.
Figures patch_figures(const ElasticMethod& method, std::size_t p, const Patch& patch);

/// A patch's figures in one frame: energy_before, energy_after, iterations, solves,
/// solve_iterations, stop, converged, first_order_gain, first_order_share, held, flips,
/// window_returned.
Figures report_figures(const ElasticReport& report);

/// The stop says the slid patch is stationary ("converged", "at rest"), or nothing slid (skipped).
bool converged(const ElasticReport& report);

/// The first-order gain left as a share of the frame's energy (0 without energy).
double first_order_share(const ElasticReport& report);

/// A patch's stop and its measure for the log: "small gain, first-order gain left 3.1%".
std::string convergence_text(const ElasticReport& report);

/// The report's sums over every patch of every frame: iterations, held, flips, window_returned,
/// not_converged.
struct ElasticTotals {
  long long iterations = 0, held = 0, flips = 0, window_returned = 0;
  long long not_converged = 0;  ///< patch-frames whose stop is not "converged" or "at rest"
  void add(const ElasticReport& report);
  Figures figures() const;
};

/// Whether a frame's --window mean costs it ten points of its energy or more: `after`, the energy
/// written, is above `own`, its own slides' energy, by more than a tenth of `before`, the frame's
/// energy (sums over the frame's free patches). The one threshold of the frame's line ("X% without
/// the window", frame_summary) and of the run's count of costly frames (pipeline/log_lines.h).
bool window_mean_costly(double before, double after, double own);

/// A frame's log summary: the most steps of any patch, the energy left as a share of the frame's,
/// the flips, `max_slide` (", max slide X") among them, the vertices written at their own slide
/// instead of --window's mean (when any), and the energy left without the window where its mean
/// costs ten points or more (window_mean_costly). `report(p)`: patch p's report.
std::string frame_summary(const std::vector<Patch>& patches,
                          const std::function<const ElasticReport&(std::size_t)>& report,
                          const std::string& max_slide);

/// A patch's -v line in a frame, up to its slide figures ("elastic 12 it (converged), ...").
std::string patch_summary(const ElasticReport& report);

}  // namespace skinslide
