// One frame: each patch slid by the run's method (pipeline/method.h), then what both methods
// share: the slid vertices gathered for the transfer, the slide figures.
#pragma once

#include <span>
#include <vector>

#include "core/types.h"
#include "locate/id_raster.h"
#include "pipeline/bind_setup.h"
#include "pipeline/method.h"
#include "mesh/slid_vertices.h"

namespace skinslide {

/// What happened to one patch in one frame.
struct PatchFrameReport {
  MethodReport method;  ///< the method's own figures
  /// Every vertex of the patch is at its bind position to float32 precision (a point cache's
  /// sample of the bind pose): the patch comes back unchanged, as the bind does; `method` keeps
  /// what the method found, `moved` is 0.
  bool at_rest = false;
  int moved = 0;          ///< free vertices written (weight > 0)
  double max_slide = 0;   ///< largest |output - frame| (frame units, after weights)
  double mean_slide = 0;  ///< mean over the vertices the method placed
  /// Edge-length spread: std of log(L / L_bind) over the patch's bars (bars of zero length
  /// skipped), in the frame and in the output. Below `spread_frame` = sliding evened the stretch.
  /// Computed only when FrameExtras::edge_spread asks for it (0 otherwise).
  double spread_frame = 0;
  double spread_slid = 0;
  double solve_seconds = 0;     ///< wall time of the frame net or relaxation (not deterministic)
  double locate_seconds = 0;    ///< ID image and point location
  double transfer_seconds = 0;  ///< 3D positions, weights, spreads
  /// The 2D picture of the frame (PatchSlide::net): the paper's frame net, or where the vertices
  /// slid to in the elastic method's chart.
  Positions2 frame_net;
  bool frame_in_bind_net = false;  ///< PatchSlide::frame_in_bind_net
  IdImage id_image;                ///< the lookup image (kept only with FrameExtras::id_image_size)
};

struct FrameResult {
  SlidVertices slid;
  std::vector<PatchFrameReport> patches;  ///< parallel to BindSetup::patches
};

/// What slide_frame computes besides the slid vertices, for dumps and reports: each costs time
/// on every frame (the spreads a log per bar, twice: tests/bench/README.md "Performance").
struct FrameExtras {
  int id_image_size = 0;     ///< > 0: keep each patch's ID lookup image, this many pixels a side
  bool edge_spread = false;  ///< PatchFrameReport::spread_frame and spread_slid
};

/// One frame's elastic relaxation of every patch (an empty result for a skipped patch), each with
/// its wall time: what a window over the neighbouring frames averages (frame_window.h).
struct FrameRelaxations {
  std::vector<ElasticResult> patches;  ///< parallel to BindSetup::patches
  std::vector<double> seconds;         ///< per patch, the relaxation's wall time
};

/// Relaxes every patch of one frame as slide_frame does, without writing anything: a patch at
/// rest (every vertex at its bind position to float32 precision) keeps its start, as slide_frame
/// writes it. Pure (the timings aside). \pre setup.method is the elastic method.
/// 	hrow Error as slide_frame.
FrameRelaxations relax_frame(const BindSetup& setup, std::span<const Vec3> frame);

/// What slide_frame writes under a window (frame_window.h): per patch this frame's own
/// relaxation and the window's mean of chart points (window_mean.h).
struct WindowedFrame {
  const FrameRelaxations* own = nullptr;
  std::vector<Positions2> mean;  ///< parallel to BindSetup::patches; empty for a skipped patch
};

/// Slides one frame. `frame` holds the deformed positions of every mesh vertex (#V).
/// A free vertex v of weight w = setup.weight[v] (1 when empty) is written at
/// frame + w (slid - frame): exactly `slid` for w = 1; not written at all for w = 0.
/// Pure: the result depends only on (setup, frame) (the *_seconds timings aside). With `window`
/// (elastic only), each patch is written at the window's mean instead of its own relaxation, which
/// is not repeated: the result then depends on (setup, frame, window).
/// \throw Error(Input) when `frame` does not have the bind's vertex count.
/// \throw Error(Numeric) when a solve fails or a result is not finite.
FrameResult slide_frame(const BindSetup& setup, std::span<const Vec3> frame,
                        const FrameExtras& extras = {}, const WindowedFrame* window = nullptr);

/// A patch's figures in a frame, in the report's order: the method's (report_figures), then the
/// slide's (at_rest, moved, max_slide, mean_slide, spread_frame, spread_slid).
Figures frame_figures(const PatchFrameReport& report);

}  // namespace skinslide
