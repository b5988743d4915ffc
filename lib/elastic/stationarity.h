// How far a slid patch is from a first-order stationary point of its energy on the frame's
// faceted surface (lib/elastic/README.md rule 10): the measure behind the stop "converged". (On a
// blended surface, --blend, the surface is smooth and the descent is the gradient's tangent part.)
// Phi is piecewise linear, so the energy has kinks where a vertex sits on a chart edge or node,
// and a minimum often sits on one: there the gradient never vanishes, but no direction goes
// down. The measure is therefore one-sided: per moving vertex the steepest first-order descent
// over every direction it can leave in (each facet around it with that facet's slope). The
// energy's first-order change along any joint step is the sum of the vertices' own one-sided
// changes (each vertex's position depends on its own chart point only), so the patch is
// stationary exactly when every vertex's descent is zero.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/types.h"
#include "elastic/arap.h"
#include "elastic/line_search.h"
#include "elastic/step_direction.h"

namespace skinslide {

/// What the energy's own curvature needs: its triangles, its stretch s, and per patch vertex
/// (local id) its movable index or -1.
struct CurvatureInputs {
  const ArapTriangles& mesh;
  double scale = 1;
  const std::vector<Index>& movable_slot;
};

/// The first-order gain left, with rho_i each moving vertex's steepest one-sided descent
/// (steepest_descent): two estimates of what a Newton step along the descents would gain, each
/// an energy (compare it with the frame's), both zero exactly at a stationary point.
struct FirstOrderGain {
  /// In the bind's metric K, 1/2 rho^T (K x I3)^-1 rho: the patch's long, smooth modes included
  /// (a vertex-by-vertex sum, rho_i^2 / 2 K_ii, missed them by the metric's condition number).
  double bind_metric = 0;
  /// With the energy's own curvature H (the rotations refitted, arap_curvature) in the frame's
  /// smooth tangent planes, 1/2 b^T (Q^T H Q)^-1 b with b = Q^T rho, by conjugate gradients
  /// preconditioned by K's factor. H is softer than K where triangles may turn (bending, a
  /// twist): there the bind's metric under-reads what further rotation fits reach, and this one
  /// reads close to it (tests/bench/stress.md "A stronger reference, and a measure that sees
  /// rotations").
  double curvature = 0;
  double larger() const { return std::max(bind_metric, curvature); }
};

/// \param gradient the energy's 3D gradient per patch vertex (local ids) at `state`.
/// \param short_of a gain above which the patch is short of stationary whatever the curvature
/// reads: once the bind's metric reads more, the curvature's estimate is not made (`curvature`
/// stays 0; larger() is then a lower bound, and above `short_of` either way).
FirstOrderGain stationarity(const FrameSurface& surface, const std::vector<Index>& movable,
                            const SlideState& state, const Positions3& gradient,
                            const ElasticMetric& metric, const CurvatureInputs& curvature,
                            double short_of = INFINITY);

/// The steepest first-order descent of a point moving on the faceted surface from chart point
/// `where` (at chart node `node` when >= 0) against the 3D gradient g: rate times unit direction,
/// zero when no direction goes down. Facets with no area are not left through.
Vec3 steepest_descent(const FrameSurface& surface, Index node, const ChartPoint& where,
                      const Vec3& g);

/// The same on the blended surface (smooth), from chart point u on patch triangle t: minus g's
/// part in the surface's tangent plane there; zero where it has none (the frame crushed there).
Vec3 blended_descent(const FrameSurface& surface, Index t, const Vec2& u, const Vec3& g);

}  // namespace skinslide
