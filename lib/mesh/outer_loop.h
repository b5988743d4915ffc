// Which boundary loop of a patch is its outer border (README "The method, exactly", rule 3): both
// methods put it on their chart's border, the elastic one on a circle, the paper's on the square.
#pragma once

#include <vector>

#include "core/types.h"

namespace skinslide {

/// Relative tolerance of the tie rules of loops: their lengths here, the square's corners' arc
/// lengths (paper/square_boundary.h). A loop sampled uniformly puts a tie exactly between two
/// candidates, where round-off alone would otherwise choose.
constexpr double kTieRelative = 1e-9;

/// The outer loop: the longest in 3D. Loops within kTieRelative (relative) of the longest tie;
/// among them the one whose start (smallest) vertex id is smallest wins.
/// `lengths`, `starts`: one entry per loop. \pre at least one loop.
Index outer_loop(const std::vector<double>& lengths, const std::vector<Index>& starts);

/// 3D length of a closed loop of points (including the closing edge).
double loop_length(const Positions3& loop_points);

}  // namespace skinslide
