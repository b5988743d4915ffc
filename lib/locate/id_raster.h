// The triangle-ID lookup image of a 2D net (Yang & Zhang 2010, section III.F).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/types.h"

namespace skinslide {

/// The default side of an ID image in pixels (--lookup-size): --locate image and --dump.
constexpr int kLookupSize = 1024;

/// A square image over the unit square [0,1]^2. Pixel (i, j) covers
/// [i/size, (i+1)/size) x [j/size, (j+1)/size) and is stored at ids[j*size + i] (row 0 = v = 0,
/// the bottom of the net). Value 0 = no triangle, t+1 = triangle t of the net.
struct IdImage {
  int size = 0;
  std::vector<std::uint32_t> ids;

  std::uint32_t at(int i, int j) const { return ids[static_cast<size_t>(j) * size + i]; }
};

/// Rasterises `triangles` of `net` (2D positions, any orientation) into a size x size image.
/// A pixel gets the lowest-index triangle that covers its centre (edges inclusive), so the
/// image does not depend on rasterisation order. Degenerate triangles cover nothing.
/// \pre size >= 1; every triangle index < net.size().
IdImage id_raster(const Positions2& net, const std::vector<Triangle>& triangles, int size);

}  // namespace skinslide
