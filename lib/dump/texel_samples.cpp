#include "dump/texel_samples.h"

#include "core/check.h"
#include "locate/barycentric.h"

namespace skinslide {

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
      // The same area test as point location, so the weights are the ones a vertex at this
      // texel centre would get. id_raster() never puts a degenerate triangle in a pixel.
      const Barycentric w =
          barycentric(Vec2((i + 0.5) / size, (j + 0.5) / size), net[t[0]], net[t[1]], net[t[2]]);
      SKINSLIDE_CHECK(w.ok, "degenerate triangle in the ID image");
      TexelSample& s = samples[static_cast<size_t>(j) * size + i];
      s.triangle = static_cast<Index>(id - 1);
      s.weight = w.w;
    }
  }
  return samples;
}

}  // namespace skinslide
