#include "dump/slide_field.h"

#include "core/check.h"
#include "dump/texel_samples.h"

namespace skinslide {

SlideField slide_field(const Positions2& bind_net, const Positions2& frame_net,
                       const std::vector<Triangle>& triangles, int size) {
  SKINSLIDE_CHECK(frame_net.size() == bind_net.size(), "bind and frame nets differ in size");
  const std::vector<TexelSample> samples = texel_samples(bind_net, triangles, size);
  SlideField field;
  field.size = size;
  field.x.assign(samples.size(), 0.0f);
  field.y.assign(samples.size(), 0.0f);
  for (int j = 0; j < size; ++j) {
    for (int i = 0; i < size; ++i) {
      const size_t k = static_cast<size_t>(j) * size + i;
      const TexelSample& s = samples[k];
      if (s.triangle < 0) continue;
      const Triangle& t = triangles[s.triangle];
      const Vec2 u((i + 0.5) / size, (j + 0.5) / size);
      const Vec2 q = s.weight[0] * frame_net[t[0]] + s.weight[1] * frame_net[t[1]] +
                     s.weight[2] * frame_net[t[2]];
      field.x[k] = static_cast<float>(q.x() - u.x());
      field.y[k] = static_cast<float>(q.y() - u.y());
    }
  }
  return field;
}

}  // namespace skinslide
