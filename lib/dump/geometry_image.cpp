#include "dump/geometry_image.h"

#include "core/check.h"
#include "dump/coverage.h"
#include "dump/texel_samples.h"

namespace skinslide {

GeometryImage geometry_image(const Positions2& net, const std::vector<Triangle>& triangles,
                             const Positions3& points, int size) {
  SKINSLIDE_CHECK(points.size() == net.size(), "one 3D point per net vertex");
  const std::vector<TexelSample> samples = texel_samples(net, triangles, size);
  GeometryImage image;
  image.size = size;
  image.x.assign(samples.size(), 0.0f);
  image.y.assign(samples.size(), 0.0f);
  image.z.assign(samples.size(), 0.0f);
  for (size_t k = 0; k < samples.size(); ++k) {
    const TexelSample& s = samples[k];
    if (s.triangle < 0) continue;
    const Triangle& t = triangles[s.triangle];
    const Vec3 p =
        s.weight[0] * points[t[0]] + s.weight[1] * points[t[1]] + s.weight[2] * points[t[2]];
    image.x[k] = static_cast<float>(p.x());
    image.y[k] = static_cast<float>(p.y());
    image.z[k] = static_cast<float>(p.z());
  }
  image.coverage = coverage_image(net, triangles, size);
  return image;
}

}  // namespace skinslide
