// The outer boundary loop on the unit square (Yang & Zhang 2010, section III.B); which loop is
// the outer one: mesh/outer_loop.h.
#pragma once

#include <array>
#include <vector>

#include "core/types.h"

namespace skinslide {

struct SquareBoundary {
  std::array<Index, 4> corners{};  ///< positions in the loop of the corners (0,0) (1,0) (1,1) (0,1)
  Positions2 positions;            ///< 2D position of each loop vertex on the square's edges
};

/// Places a loop (points in walking order, starting at the loop's first vertex) on the unit square.
/// Corner 0 is the start vertex; corner j (j = 1..3) is the vertex whose cumulative arc length is
/// nearest to j*L/4 (near-ties within kTieRelative*L go to the earlier vertex), forced strictly
/// increasing and leaving room for the remaining corners. Vertices between two corners are spaced
/// on that side by arc length.
/// \throw Error(Input) when the loop has fewer than 4 vertices or zero length.
SquareBoundary square_positions(const Positions3& loop_points);

/// Places a loop on the unit square with chosen corners (`--corners`): `corners` are positions in
/// the loop (points in walking order) of (0,0) (1,0) (1,1) (0,1), distinct and in walking order
/// cyclically (corners[0] need not be 0). Vertices between two corners are spaced on that side by
/// arc length, as above.
/// \throw Error(Input) when the corners are not distinct and in walking order, or a side between
///        two corners has zero length.
SquareBoundary square_positions(const Positions3& loop_points, const std::array<Index, 4>& corners);

}  // namespace skinslide
