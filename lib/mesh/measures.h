// Measures both methods take of a patch: its bars' 3D lengths (the bind's, a frame's) and the
// folds of a 2D picture of it (the paper's nets, the elastic method's chart), which the report
// counts as flips.
#pragma once

#include <array>
#include <vector>

#include "core/types.h"

namespace skinslide {

/// 3D length of each bar. `points`: positions indexed by the bars' node ids.
std::vector<double> bar_lengths(const Positions3& points,
                                const std::vector<std::array<Index, 2>>& bars);

/// The largest span (bounding-box diagonal) a patch may have, in the mesh's units. Both methods
/// square lengths and sum products of them (the elastic energy grows as a length to the 4th),
/// which overflow a double from about 1e77; below this they stay finite with room to spare.
inline constexpr double kLargestPatchSpan = 1e60;

/// The smallest span (bounding-box diagonal) a patch may have, unless it is 0 (every vertex on
/// one point: a degenerate frame the methods handle, or a bind refused as having zero length).
/// A frame is compared with the bind in float32 (at rest: written unchanged), and point caches
/// hold float32: both keep float32's relative precision only while its smallest step, 1.4e-45,
/// is below 6e-8 of the span, i.e. from a span of about 2e-38; 1e-30 leaves a factor 1e8 above
/// that limit (the slide at scaled-down meshes: tests/bench/README.md "Tiny and huge patches").
inline constexpr double kSmallestPatchSpan = 1e-30;

/// Checks that `points` (a patch's positions; `ids` their mesh vertex ids, for the message) span
/// at most kLargestPatchSpan and, unless they all lie on one point, at least kSmallestPatchSpan.
/// \throw Error(Input) "vertex V at (x, y, z): coordinates too large: ..." or "... coordinates
///        too small: ..." naming the vertex of the largest coordinate.
void require_computable_span(const Positions3& points, const std::vector<Index>& ids);

/// How many triangles of a net do not keep the orientation of the majority.
struct Folds {
  int flipped = 0;              ///< zero area or of the minority sign (what reports call flips)
  std::vector<Index> reversed;  ///< strictly of the minority sign, ascending: the folds that
                                ///< cover points a second time
};
Folds count_folds(const Positions2& net, const std::vector<Triangle>& triangles);

/// Triangles of `net` whose signed area is zero or of the minority sign (folds of the net).
int flipped_triangles(const Positions2& net, const std::vector<Triangle>& triangles);

/// True when a slid triangle's normal `slid` does not point along its frame triangle's normal
/// `frame` (zero, or against it); false when the frame triangle has no area (`frame` zero).
/// Both are scaled to a largest component of 1 first: the product of two normals of triangles
/// near 1e-160 in size underflows to 0, which would read a triangle left exactly where the frame
/// has it as turned.
bool turned_against(const Vec3& slid, const Vec3& frame);

/// Triangles turned against their frame triangle (turned_against) when `frame`'s vertices move to
/// `slid` (both #V of the mesh or of the patch, as `triangles` index them): a slide's folds.
int turned_triangles(const std::vector<Triangle>& triangles, const Positions3& frame,
                     const Positions3& slid);

}  // namespace skinslide
