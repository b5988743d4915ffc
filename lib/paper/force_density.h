// Force densities of the bar net (Yang & Zhang 2010, section III.C, equation (2)).
#pragma once

#include <vector>

#include "core/types.h"

namespace skinslide {

/// How a bar's force density q follows its length L (Lmin, Lmax per patch).
enum class Density {
  Paper,    ///< q = max(1 - L/Lmax, q_floor): Yang & Zhang 2010, equation (2)
  Inverse,  ///< q = max(Lmin/L, q_floor): long bars soft (also spelled `length`: q ~ 1/L)
  Uniform,  ///< q = 1: Tutte's barycentric embedding
};

/// Force density of each bar from its length, normalised per patch (Lmin, Lmax of `lengths`):
///  - Paper:   q = max(1 - L/Lmax, q_floor); without the floor the longest bar has q = 0.
///  - Inverse: q = max(Lmin/L, q_floor), with L clamped to >= 1e-12 Lmax (long bars soft).
///  - Uniform: q = 1.
/// Output: one q per bar, dimensionless, in [q_floor, 1].
/// \throw Error(Input) when every bar has zero length (a collapsed patch).
std::vector<double> force_densities(const std::vector<double>& lengths, Density density,
                                    double q_floor);

}  // namespace skinslide
