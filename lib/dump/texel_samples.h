// Where each texel centre of a square image over the unit square falls in a 2D net: a triangle
// and barycentric weights. The shared first step of the geometry image and the slide field.
#pragma once

#include <array>
#include <vector>

#include "core/types.h"
#include "locate/id_raster.h"

namespace skinslide {

/// A texel centre located in a net: `triangle` = -1 where no triangle covers it.
struct TexelSample {
  Index triangle = -1;
  std::array<double, 3> weight{0.0, 0.0, 0.0};  ///< on the triangle's corners, sum 1
};

/// The sample of every texel centre ((i + 0.5)/size, (j + 0.5)/size) of a size x size image,
/// stored at [j*size + i] (row 0 = v = 0, as IdImage). The triangle is the one id_raster()
/// puts in that pixel (the lowest index covering the centre, edges inclusive), so it is the
/// triangle point location's lookup image names; the weights are area ratios (Yang & Zhang 2010,
/// section III.F): a = Area(PBC)/Area(ABC), b = Area(APC)/Area(ABC), c = Area(ABP)/Area(ABC).
/// \pre size >= 1; every triangle index < net.size().
std::vector<TexelSample> texel_samples(const Positions2& net,
                                       const std::vector<Triangle>& triangles, int size);

/// Same, from an ID image already rasterised from (net, triangles).
std::vector<TexelSample> texel_samples(const Positions2& net,
                                       const std::vector<Triangle>& triangles, const IdImage& ids);

}  // namespace skinslide
