// Point location in a 2D net through its ID image, with an exact fallback.
#pragma once

#include <array>
#include <vector>

#include "core/types.h"
#include "locate/id_raster.h"

namespace skinslide {

struct Location {
  Index triangle = -1;                    ///< index into the net's triangles
  std::array<double, 3> weight{1, 0, 0};  ///< barycentrics on the triangle's corners, sum 1
  bool fallback = false;                  ///< not found through the image (see locate_points)
};

/// Finds, for each point, the net triangle that holds it (Yang & Zhang 2010, section III.F).
/// Candidates are the triangles of the point's pixel and its 8 neighbours in `image` (built by
/// id_raster from the same net); a candidate holds the point when its area-based barycentrics
/// are all >= -kInsideEps. Where several hold it, the largest smallest barycentric wins, then the
/// lower triangle index. Where no candidate holds it (triangles smaller than a pixel, points just
/// outside the net, a folded net) the fallback searches every triangle whose bounding box holds
/// the point by the same rule, and failing that takes the nearest triangle (lowest index on ties)
/// with the barycentrics of the closest point (all in [0,1]). Never NaN.
/// \param points 2D points (#P); net: 2D node positions; triangles index `net`.
std::vector<Location> locate_points(const Positions2& points, const Positions2& net,
                                    const std::vector<Triangle>& triangles, const IdImage& image);

}  // namespace skinslide
