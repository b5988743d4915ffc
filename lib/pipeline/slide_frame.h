// One frame: frame net, point location (a walk or an ID image), transfer.
#pragma once

#include <string>
#include <vector>

#include "core/types.h"
#include "locate/id_raster.h"
#include "pipeline/bind_setup.h"
#include "slide/transfer.h"
#include "unwrap/bar_net.h"

namespace skinslide {

/// What happened to one patch in one frame.
struct PatchFrameReport {
  int cg_iterations = 0;      ///< CG iterations (the larger of the x and y solves)
  double cg_residual = 0;     ///< final |r|/|b|
  bool direct_solve = false;  ///< CG did not converge; the net was solved directly
  int located_in_image = 0;   ///< vertices found through the ID image or the walk
  int located_fallback = 0;   ///< vertices found by the nearest-triangle fallback
  int frame_net_flips = 0;    ///< frame-net triangles of the minority orientation
  double max_slide = 0;       ///< largest |output - frame| (frame units, after weights)
  double mean_slide = 0;      ///< mean over free vertices
  int moved = 0;              ///< free vertices written (weight > 0)
  /// Edge-length spread: std of log(L / L_bind) over the patch's bars (bars of zero length
  /// skipped), in the frame and in the output. Below `spread_frame` = sliding evened the stretch.
  /// Computed only when FrameExtras::edge_spread asks for it (0 otherwise).
  double spread_frame = 0;
  double spread_slid = 0;
  /// Elastic method (SlideMethod::Elastic) only: the relaxation's figures (relax.h).
  double energy_before = 0;  ///< the frame's elastic energy against the bind
  double energy_after = 0;   ///< after the slide, never above energy_before
  int iterations = 0;        ///< steps taken
  int held = 0;              ///< vertex-steps held in place to keep a step a descent
  int slid_flips = 0;        ///< slid triangles whose normal turns against the frame's (want 0)
  std::string stop;          ///< why the relaxation stopped
  double solve_seconds = 0;     ///< wall time of the frame net or relaxation (not deterministic)
  double locate_seconds = 0;    ///< ID image and point location
  double transfer_seconds = 0;  ///< 3D positions, weights, spreads
  /// 2D position of every local vertex in this frame's net (paper), or where it slid to in the
  /// patch's chart (elastic)
  Positions2 frame_net;
  IdImage id_image;             ///< the lookup image (kept only with FrameExtras::id_image)
};

struct FrameResult {
  SlidVertices slid;
  std::vector<PatchFrameReport> patches;  ///< parallel to BindSetup::patches
};

/// The frame-net solver settings of `options` (CG tolerance and iteration cap).
FrameNetOptions frame_net_options(const SlideOptions& options);

/// The method a patch's nets are solved by: the one named, or for Auto, Multigrid from
/// kMultigridFreeNodes free nodes on and Cholesky below.
FrameNetMethod frame_net_method(FrameSolver solver, std::ptrdiff_t free_nodes);

/// What slide_frame computes besides the slid vertices, for dumps and reports: each costs time
/// on every frame (the spreads a log per bar, twice: about 5% of a 40k-vertex frame).
struct FrameExtras {
  bool id_image = false;     ///< keep each patch's ID lookup image (PatchFrameReport::id_image)
  bool edge_spread = false;  ///< PatchFrameReport::spread_frame and spread_slid
};

/// Slides one frame. `frame` holds the deformed positions of every mesh vertex (#V).
/// A free vertex v of weight w = setup.weight[v] (1 when empty) is written at
/// frame + w (slid - frame): exactly `slid` for w = 1; not written at all for w = 0.
/// Pure: the result depends only on (setup, frame) (the *_seconds timings aside).
/// \throw Error(Numeric) when a solve fails or a result is not finite.
FrameResult slide_frame(const BindSetup& setup, const Positions3& frame,
                        const FrameExtras& extras = {});

}  // namespace skinslide
