// How far a slid patch is from a first-order stationary point of its energy on the frame's
// faceted surface (lib/elastic/README.md rule 10): the measure behind the stop "converged".
// Phi is piecewise linear, so the energy has kinks where a vertex sits on a chart edge or node,
// and a minimum often sits on one: there the gradient never vanishes, but no direction goes
// down. The measure is therefore one-sided: per moving vertex the steepest first-order descent
// over every direction it can leave in (each facet around it with that facet's slope). The
// energy's first-order change along any joint step is the sum of the vertices' own one-sided
// changes (each vertex's position depends on its own chart point only), so the patch is
// stationary exactly when every vertex's descent is zero.
#pragma once

#include <vector>

#include "core/types.h"
#include "elastic/line_search.h"

namespace skinslide {

struct Stationarity {
  /// sum over moving vertices of descent_i^2 / (2 K_ii): what each vertex moving alone down its
  /// steepest one-sided slope would gain (to second order in its own stiffness K_ii), summed.
  /// An energy: compare it with the frame's. Zero at a stationary point.
  double gain = 0;
  Index worst = -1;  ///< the local id of the vertex with the largest share, -1 when none
};

/// \param gradient the energy's 3D gradient per patch vertex (local ids) at `state`.
/// \param stiffness per moving vertex K_ii (the metric's diagonal).
Stationarity stationarity(const FrameSurface& surface, const std::vector<Index>& movable,
                          const SlideState& state, const Positions3& gradient,
                          const std::vector<double>& stiffness);

/// The steepest first-order descent rate (>= 0, per unit of 3D length) of a point moving on the
/// faceted surface from chart point `where` (at chart node `node` when >= 0) against the 3D
/// gradient g: 0 when no direction goes down. Facets with no area are not left through.
double one_sided_descent(const FrameSurface& surface, Index node, const ChartPoint& where,
                         const Vec3& g);

}  // namespace skinslide
