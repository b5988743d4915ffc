// The paper's method as a run holds and tells it: every patch's set-up, and the method's figures
// for the report and its log text. pipeline/method.h dispatches to these and to
// elastic/elastic_method.h, which has the same shape.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/figures.h"
#include "core/types.h"
#include "mesh/patch.h"
#include "paper/paper_slide.h"

namespace skinslide {

/// The paper's method's bind-time data: its options and every patch's set-up.
struct PaperMethod {
  PaperOptions options;
  std::vector<PaperSetup> patches;  ///< parallel to BindSetup::patches; no solver when skipped
};

/// Sets patch `p` up (paper_setup) into its slot of `method`. Arguments as paper_setup.
void set_up_patch(PaperMethod& method, std::size_t p, Patch& patch, const Positions3& points,
                  const CornerChoice& corners, bool spare_thread);

/// The square's corners of a patch as mesh vertex ids, and whether they were chosen.
struct SquareCorners {
  std::array<Index, 4> vertices{};
  bool chosen = false;
};

/// Patch `p`'s corners; none for a skipped patch.
std::optional<SquareCorners> square_corners(const PaperMethod& method, std::size_t p,
                                            const Patch& patch);

/// Slides patch `p` in one frame (nothing moves in a skipped patch). Arguments as paper_slide.
PaperSlide slide_patch(const PaperMethod& method, std::size_t p, const Patch& patch,
                       const Positions3& points, const std::vector<double>& weight,
                       int id_image_size);

/// For the bind's log line: "method paper, density inverse, holes fill".
std::string method_label(const PaperMethod& method);

/// The report's entry for patch `p` at bind: counts, loops, corners, corners_chosen, skipped,
/// bind_net_flips, frame_solver.
Figures patch_figures(const PaperMethod& method, std::size_t p, const Patch& patch);

/// A patch's figures in one frame: cg_iterations, cg_residual, direct_solve, located_in_image,
/// located_fallback, frame_net_flips, flips (slid triangles turned against the frame's).
Figures report_figures(const PaperReport& report);

/// The report's sums over every patch of every frame: cg_iterations, direct_solves, fallbacks,
/// frame_net_flips, flips.
struct PaperTotals {
  long long cg_iterations = 0, direct_solves = 0, fallbacks = 0, frame_net_flips = 0, flips = 0;
  void add(const PaperReport& report);
  Figures figures() const;
};

/// A frame's log summary: the frame nets' solvers, each once in patch order with its most
/// iterations, `max_slide` (", max slide X"), the locator's fallbacks. `report(p)`: patch p's.
std::string frame_summary(const PaperMethod& method, const std::vector<Patch>& patches,
                          const std::function<const PaperReport&(std::size_t)>& report,
                          const std::string& max_slide);

/// A patch's -v line in a frame, up to its slide figures ("Cholesky, located 120 + 0 fallback,
/// net flips 0").
std::string patch_summary(const PaperMethod& method, std::size_t p, const PaperReport& report);

}  // namespace skinslide
