// The outer boundary loop on the unit square (Yang & Zhang 2010, section III.B).
#pragma once

#include <array>
#include <vector>

#include "core/types.h"

namespace skinslide {

/// Relative tolerance of the tie rules below (loop lengths, corner arc lengths).
constexpr double kTieRelative = 1e-9;

/// Which loop goes on the square: the longest in 3D. Loops within kTieRelative (relative) of the
/// longest tie; among them the one whose start (smallest) vertex id is smallest wins.
/// `lengths`, `starts`: one entry per loop. \pre at least one loop.
Index outer_loop(const std::vector<double>& lengths, const std::vector<Index>& starts);

/// 3D length of a closed loop of points (including the closing edge).
double loop_length(const Positions3& loop_points);

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
/// 	hrow Error(Input) when the corners are not distinct and in walking order, or a side between
///        two corners has zero length.
SquareBoundary square_positions(const Positions3& loop_points, const std::array<Index, 4>& corners);

}  // namespace skinslide
