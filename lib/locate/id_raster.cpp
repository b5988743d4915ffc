#include "locate/id_raster.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "locate/barycentric.h"

namespace skinslide {

IdImage id_raster(const Positions2& net, const std::vector<Triangle>& triangles, int size) {
  SKINSLIDE_CHECK(size >= 1, "ID image size");
  IdImage img;
  img.size = size;
  img.ids.assign(static_cast<size_t>(size) * size, 0);
  const double inv = 1.0 / size;
  // Pixel i holds centre (i + 0.5)/size; the pixels whose centres can lie in [lo, hi].
  auto first_pixel = [&](double lo) {
    return std::clamp(static_cast<int>(std::ceil(lo * size - 0.5)), 0, size);
  };
  auto last_pixel = [&](double hi) {
    return std::clamp(static_cast<int>(std::floor(hi * size - 0.5)), -1, size - 1);
  };
  for (size_t t = 0; t < triangles.size(); ++t) {
    const Vec2& a = net[triangles[t][0]];
    const Vec2& b = net[triangles[t][1]];
    const Vec2& c = net[triangles[t][2]];
    const int i0 = first_pixel(std::min({a.x(), b.x(), c.x()}));
    const int i1 = last_pixel(std::max({a.x(), b.x(), c.x()}));
    const int j0 = first_pixel(std::min({a.y(), b.y(), c.y()}));
    const int j1 = last_pixel(std::max({a.y(), b.y(), c.y()}));
    const auto id = static_cast<std::uint32_t>(t + 1);
    for (int j = j0; j <= j1; ++j) {
      std::uint32_t* row = img.ids.data() + static_cast<size_t>(j) * size;
      for (int i = i0; i <= i1; ++i) {
        if (row[i] != 0) continue;  // a lower-index triangle already holds this centre
        const Barycentric w = barycentric(Vec2((i + 0.5) * inv, (j + 0.5) * inv), a, b, c);
        if (w.ok && w.min() >= 0) row[i] = id;
      }
    }
  }
  return img;
}

}  // namespace skinslide
