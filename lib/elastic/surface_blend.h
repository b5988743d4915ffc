// The blended surface's bind-time data over one chart (blended_surface.h builds it and evaluates
// the surface; surface_map.h's FrameSurface points to it): plain data in its own header, so that
// the frame's surface and the blend it may carry include it without including each other.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "core/types.h"

namespace skinslide {

/// One patch triangle's edges in the chart, edge k opposite corner k: the inward unit normal of
/// its line and its offset (u's signed distance from the line is normal . u - offset, positive
/// inside), and its blend half-width (0: the patch's border or a hole's, not blended).
struct BlendEdges {
  std::array<Vec2, 3> normal;
  std::array<double, 3> offset;
  std::array<double, 3> width;
  /// How far from the triangle its weight reaches: it fades from 1 at distance reach / 2 to 0 at
  /// `reach`, the distance of the nearest node the bands would reach that is not its corner
  /// (infinite: no such node, no fade).
  double reach = INFINITY;
};

/// Bind-time data of the blend over one chart: plain data, read-only afterwards.
struct SurfaceBlend {
  std::vector<BlendEdges> edges;  ///< per patch triangle
  /// CSR per patch triangle t: the patch triangles whose weight may be non-zero on t, t first.
  std::vector<Index> around_start;
  std::vector<Index> around;
  /// Per patch triangle the box (lo x, lo y, hi x, hi y) of where its weight is not zero.
  std::vector<std::array<double, 4>> support;
};

}  // namespace skinslide
