// The elastic slide as a fixed map of its frame (lib/elastic/README.md "The map"): from the
// frame's own positions, a fixed number of passes, each made of continuous steps only, so the
// slide is a continuous function of the frame by construction. A tiny change of the frame is a
// tiny change of the slide: nothing in it is a decision (no line search, no holds, no tolerance,
// no escalation), and it is smooth in time wherever the motion is.
//
// A pass: every triangle's rotation fitted to the slid patch (the polar factor of its
// deformation gradient, ARAP's local step: Sorkine & Alexa 2007), weighted down smoothly where
// the slid triangle is crushed towards a line (its polar factor jumps as a singular value passes
// zero); one Gauss-Newton step of the held-rotation energy in the chart through a continuous
// field of surface Jacobians (each chart node's the area-weighted mean of its triangles', blended
// barycentrically), damped (Levenberg-Marquardt) and solved by a fixed number of conjugate
// gradients from zero preconditioned by the bind's factor; a fold guard that scales each
// vertex's step by a smooth function of its triangles' edge strains in the chart and in 3D (a
// continuous barrier in place of Smith & Schaefer's fold roots). The slid vertex is written on
// the frame's facets at its chart point.
#pragma once

#include "core/types.h"
#include "elastic/relax.h"
#include "elastic/surface_map.h"

namespace skinslide {

/// How the map runs: fixed counts, no tolerances.
struct SmoothMapRun {
  int passes = 2;  ///< ElasticOptions::passes
  /// Preconditioned conjugate-gradient iterations of each pass's step (each one back-solve with
  /// the bind's factor), from zero: a fixed count keeps the step a continuous function. The
  /// patch's own count, from its bind (ElasticSetup::map_step_iterations, map_step_budget).
  int step_iterations = kMapStepIterations;
};

/// The map's step budget for one patch, from its bind alone, so that every frame of the patch is
/// mapped by the same function: the fewest of kMapStepIterations, twice as many, ... up to
/// kMaxMapStepIterations conjugate gradients that solve the bind's own step system (the bind as
/// its frame: its Jacobian field, tangent frames and damping) for a fixed right side (the metric
/// applied to a fixed pseudo-random field) to kMapStepResidual of its starting residual; the
/// largest when none does. Where the bind's factor preconditions that system well (smooth,
/// well-shaped patches) this is the smallest count; slivers, needles and charts that squeeze a
/// whole head into a disk need more (lib/elastic/README.md "The map", rule M3).
/// \param bind the bind positions of the patch's vertices (local ids), as elastic_setup's.
int map_step_budget(const ElasticSetup& setup, const Positions3& bind);

/// Runs the map on one patch in one frame whose energy (`result.energy_before`) and stretch
/// (`result.scale`) are set and which is not at rest, and fills `result`: every movable vertex's
/// chart point, where it lies and its position on the frame's facets, the energy after, the
/// passes (`iterations`), the solves and their iterations. `stop` and `gain_left` are left to the
/// caller (relax.h: the same measure as the search's).
/// Pure: depends on (setup, surface, run) only; the same bits for any thread count.
void smooth_map(const ElasticSetup& setup, const FrameSurface& surface, const SmoothMapRun& run,
                ElasticResult& result);

/// The map's surface Jacobian field: per patch vertex (local id) the chart-area-weighted mean of
/// the surface Jacobians (surface_map.h surface_jacobian) of the patch triangles around it.
/// Blended barycentrically inside a triangle it is continuous across every chart edge and node.
std::vector<Mat32> vertex_jacobians(const FrameSurface& surface);

/// The field at a chart point: the barycentric blend of its triangle's corners' Jacobians.
Mat32 blended_jacobian(const Chart& chart, const std::vector<Mat32>& field, const ChartPoint& p);

/// 3 x^2 - 2 x^3 of x clamped to [0, 1]: 0 at or below 0, 1 at or above 1, C1 between.
double smoothstep(double x);

}  // namespace skinslide
