// The paper's method (Yang & Zhang 2010), one patch at a time: at bind time the patch is
// flattened onto the unit square by a force-density bar net; in every frame the patch is
// flattened again with the frame's lengths, and each free vertex's bind-net point is located in
// the frame net and carried back onto the frame's surface (README "The method, exactly").
// The same shape as the elastic method (elastic/elastic_slide.h): options, a bind-time set-up,
// a per-frame pure function returning positions and a report.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "core/types.h"
#include "locate/id_raster.h"
#include "locate/locate.h"
#include "mesh/measures.h"
#include "mesh/patch.h"
#include "paper/bar_net.h"
#include "paper/force_density.h"
#include "paper/paper_options.h"
#include "slide/patch_slide.h"

namespace skinslide {

/// The frame-net solver settings of `options` (CG tolerance and iteration cap).
FrameNetOptions frame_net_options(const PaperOptions& options);

/// The method a patch's nets are solved by: the one named, or for Auto, Multigrid from
/// kMultigridFreeNodes free nodes on and Cholesky below.
FrameNetMethod frame_net_method(FrameSolver solver, std::ptrdiff_t free_nodes);

/// The animator's corner choice for one patch (--corners): four mesh vertex ids on the patch's
/// outer loop, in the loop's walking order, for (0,0) (1,0) (1,1) (0,1).
struct CornerChoice {
  bool chosen = false;  ///< false: the corners are automatic (README rule 3)
  std::array<Index, 4> corners{};
  std::string source;  ///< the option as given, for messages ("--corners 1,2,3,4")
};

/// Bind-time precompute of one patch: plain data, immutable once built, shared by every frame.
struct PaperSetup {
  TriangleTopology topology;       ///< neighbours of the patch's triangles, for the walks
  std::array<Index, 4> corners{};  ///< local ids of the square's corners (0,0) (1,0) (1,1) (0,1)
  bool corners_chosen = false;     ///< the corners came from --corners
  std::shared_ptr<const FrameNetSolver> solver;  ///< the frame nets, reused by every frame
};

/// Sets up one patch that slides (not skipped): its outer loop on the square, its bind net (in
/// `patch.bind_net`, with `patch.bind_net_flips`), its frame-net solver.
/// \param points bind positions of the patch's vertices (local ids)
/// \param spare_thread a second thread may build the frame-net solver while the bind net is
///        solved (the same solver either way)
/// \throw Error(Usage) when the chosen corners are not in the loop's walking order.
/// \throw Error(Numeric) when the bind net cannot be solved.
PaperSetup paper_setup(Patch& patch, const Positions3& points, const PaperOptions& options,
                       const CornerChoice& corners, bool spare_thread);

/// What the paper's slide of one patch did in one frame.
struct PaperReport {
  int cg_iterations = 0;      ///< CG iterations (the larger of the x and y solves)
  double cg_residual = 0;     ///< final |r|/|b|
  bool direct_solve = false;  ///< CG did not converge; the net was solved directly
  int located_in_image = 0;   ///< vertices found through the ID image or the walk
  int located_fallback = 0;   ///< vertices found by the nearest-triangle fallback
  int frame_net_flips = 0;    ///< frame-net triangles of the minority orientation
  int slid_flips = 0;  ///< slid triangles turned against the frame's (the frame's with area only)
};

struct PaperSlide {
  PatchSlide slid;
  PaperReport report;
};

/// Slides one patch in one frame. A free vertex of slide weight w (`weight[mesh id]`, 1 when
/// `weight` is empty) is written at frame + w (slid - frame); not at all for w = 0.
/// Pure: depends on (setup, patch, points, weight, options) only (the timings aside).
/// \param points the frame's positions of the patch's vertices (local ids)
/// \param id_image_size > 0: keep the frame net's ID image at that size (PatchSlide::id_image)
/// \throw Error(Numeric) naming the vertex when a slid position is not finite.
PaperSlide paper_slide(const PaperSetup& setup, const Patch& patch, const Positions3& points,
                       const std::vector<double>& weight, const PaperOptions& options,
                       int id_image_size = 0);

}  // namespace skinslide
