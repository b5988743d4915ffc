// Coverage of a square image's texels by a 2D net: the exact fraction of each texel's area that
// the net's triangles cover. The `A` channel of the geometry image (README "Dumps").
#pragma once

#include <vector>

#include "core/types.h"
#include "locate/id_raster.h"

namespace skinslide {

/// Fraction of each texel of a size x size image over the unit square covered by `triangles` of
/// `net`: texel (i, j) is [i/size, (i+1)/size) x [j/size, (j+1)/size), stored at [j*size + i]
/// (row 0 = v = 0, as IdImage). Each triangle is clipped against each texel it touches and the
/// clipped areas are summed in triangle order, then clamped to 1 (where a folded net overlaps
/// itself). Exact up to rounding: clipped areas are summed in double and stored as float, so for
/// an unfolded net the image's sum / size^2 equals the area of the part of the net inside the unit
/// square to within 1e-7. Any orientation; degenerate triangles cover nothing.
/// \pre size >= 1; every triangle index < net.size().
std::vector<float> coverage_image(const Positions2& net, const std::vector<Triangle>& triangles,
                                  int size);

}  // namespace skinslide
