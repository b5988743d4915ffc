#include "dump/texel_samples.h"

#include "core/check.h"

namespace skinslide {
namespace {

double cross(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

}  // namespace

std::vector<TexelSample> texel_samples(const Positions2& net,
                                       const std::vector<Triangle>& triangles, int size) {
  SKINSLIDE_CHECK(size >= 1, "texel image size");
  return texel_samples(net, triangles, id_raster(net, triangles, size));
}

std::vector<TexelSample> texel_samples(const Positions2& net,
                                       const std::vector<Triangle>& triangles, const IdImage& ids) {
  const int size = ids.size;
  SKINSLIDE_CHECK(size >= 1 && ids.ids.size() == static_cast<size_t>(size) * size,
                  "ID image shape");
  std::vector<TexelSample> samples(ids.ids.size());
  for (int j = 0; j < size; ++j) {
    for (int i = 0; i < size; ++i) {
      const std::uint32_t id = ids.at(i, j);
      if (id == 0) continue;
      SKINSLIDE_CHECK(id <= triangles.size(), "ID image names a triangle the net lacks");
      const Triangle& t = triangles[id - 1];
      const Vec2& a = net[t[0]];
      const Vec2& b = net[t[1]];
      const Vec2& c = net[t[2]];
      const Vec2 p((i + 0.5) / size, (j + 0.5) / size);
      // Signed areas: the ratios are right for either orientation, and id_raster() never puts a
      // degenerate triangle in a pixel, so abc != 0.
      const double abc = cross(a, b, c);
      SKINSLIDE_CHECK(abc != 0, "degenerate triangle in the ID image");
      TexelSample& s = samples[static_cast<size_t>(j) * size + i];
      s.triangle = static_cast<Index>(id - 1);
      s.weight[1] = cross(a, p, c) / abc;
      s.weight[2] = cross(a, b, p) / abc;
      s.weight[0] = 1.0 - s.weight[1] - s.weight[2];
    }
  }
  return samples;
}

}  // namespace skinslide
