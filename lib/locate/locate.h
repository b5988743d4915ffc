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
  bool fallback = false;  ///< not found through the image or the walk (see locate_points)
};

/// Which triangles meet where, for walking a net: a pure function of the triangles, built once
/// per patch. Triangles must be consistently oriented (every inner edge run both ways).
struct TriangleTopology {
  /// Per triangle, the triangle across the edge opposite corner k (k = 0, 1, 2); -1 on a border.
  std::vector<std::array<Index, 3>> neighbour;
  /// CSR: the triangles with corner v are corner_triangles[corner_start[v] .. corner_start[v+1]),
  /// ascending.
  std::vector<Index> corner_start;
  std::vector<Index> corner_triangles;
};

/// \param vertex_count nodes of the net (#V); every triangle index < vertex_count.
TriangleTopology triangle_topology(const std::vector<Triangle>& triangles, Index vertex_count);

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

/// The same search without an image: point k is looked for by a walk through the net that starts
/// at the lowest-index triangle with corner `start[k]` (a node near the point, e.g. the vertex
/// whose bind position the point is), or, away from the reversed triangles, at the triangle that
/// held point k-1 when that triangle's first corner is nearer, and steps across the edge of the
/// most negative barycentric,
/// at most 64 + 4 sqrt(#triangles) steps, until a triangle holds the point (all barycentrics
/// >= -kInsideEps). The candidates are that triangle and every triangle sharing a corner with
/// it, chosen by the rule of locate_points. A walk that leaves the net, circles (Brent's check
/// stops it) or runs out of steps is finished, away from the reversed triangles, by a
/// breadth-first search across shared edges from where it ended, over at most 4096 triangles,
/// for a triangle that holds the point (then the same candidates); failing that, and near the
/// reversed triangles, it ends in the fallback of locate_points. Points finished
/// either way are marked `fallback`. Away from the reversed triangles a triangle that holds the
/// point strictly inside is the only candidate that can win, so the others are not evaluated there:
/// with the loops simple, the triangles of the majority orientation cover a point twice only where
/// a reversed triangle covers it too, and a zero-area triangle (three nodes on one side of the
/// square) holds no point. "Away" is outside every reversed triangle's bounding box grown by
/// kInsideEps of its size, beyond which none of them can hold the point.
/// \param start #P node ids; topology from triangle_topology(triangles, net.size()).
/// \param reversed the triangles of the minority orientation (count_folds().reversed).
std::vector<Location> locate_points_by_walk(const Positions2& points,
                                            const std::vector<Index>& start, const Positions2& net,
                                            const std::vector<Triangle>& triangles,
                                            const TriangleTopology& topology,
                                            const std::vector<Index>& reversed);

}  // namespace skinslide
