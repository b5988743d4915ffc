#include "dump/geometry_image.h"

#include <cmath>
#include <numeric>

#include <gtest/gtest.h>

#include "dump/texel_samples.h"
#include "helpers/nets.h"

namespace skinslide {
namespace {

Vec3 at(const GeometryImage& g, int i, int j) {
  const size_t k = size_t(j) * g.size + i;
  return {g.x[k], g.y[k], g.z[k]};
}

TEST(GeometryImage, AffineSurfaceIsReproducedAtEveryTexelCentre) {
  const test::TestNet g = test::grid_net(2);
  auto f = [](const Vec2& u) { return Vec3(2 * u.x() + 1, 3 * u.y() - 1, u.x() + u.y()); };
  Positions3 points;
  for (const Vec2& u : g.net) points.push_back(f(u));
  const int size = 32;
  const GeometryImage image = geometry_image(g.net, g.triangles, points, size);
  ASSERT_EQ(image.size, size);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const Vec2 c((i + 0.5) / size, (j + 0.5) / size);
      EXPECT_LT((at(image, i, j) - f(c)).norm(), 1e-6) << i << "," << j;
      EXPECT_NEAR(image.coverage[size_t(j) * size + i], 1.0, 1e-6);
    }
}

TEST(GeometryImage, HoleTexelsAreZero) {
  const test::TestNet g = test::holed_net();
  const Positions3 points = test::bent(g.net);
  const int size = 30;  // the hole is texels 10..19 in both directions
  const GeometryImage image = geometry_image(g.net, g.triangles, points, size);
  const std::vector<TexelSample> samples = texel_samples(g.net, g.triangles, size);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const bool hole = i >= 10 && i < 20 && j >= 10 && j < 20;
      const size_t k = size_t(j) * size + i;
      EXPECT_EQ(samples[k].triangle < 0, hole) << i << "," << j;
      if (hole) {
        EXPECT_EQ(at(image, i, j), Vec3::Zero());
        EXPECT_EQ(image.coverage[k], 0.0f);
      } else {
        EXPECT_NE(at(image, i, j), Vec3::Zero());
      }
    }
  const double sum = std::accumulate(image.coverage.begin(), image.coverage.end(), 0.0);
  EXPECT_NEAR(sum / (size * size), g.area, 1e-7);
}

TEST(GeometryImage, VertexPixelIsWithinAPixelOfTheVertex) {
  const test::TestNet g = test::grid_net(4);
  const Positions3 points = test::bent(g.net);
  const double stretch = test::max_stretch(g.net, g.triangles, points);
  for (int size : {16, 61, 128}) {
    const GeometryImage image = geometry_image(g.net, g.triangles, points, size);
    // A texel centre is at most half a texel diagonal from any point of its texel.
    const double bound = stretch * std::sqrt(0.5) / size + 1e-6;
    for (size_t v = 0; v < g.net.size(); ++v) {
      const int i = std::min(size - 1, int(std::floor(g.net[v].x() * size)));
      const int j = std::min(size - 1, int(std::floor(g.net[v].y() * size)));
      EXPECT_LE((at(image, i, j) - points[v]).norm(), bound) << "vertex " << v << " size " << size;
    }
  }
}

TEST(TexelSamples, WeightsReproduceTheTexelCentre) {
  const test::TestNet g = test::grid_net(3);
  const int size = 20;
  const std::vector<TexelSample> samples = texel_samples(g.net, g.triangles, size);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const TexelSample& s = samples[size_t(j) * size + i];
      ASSERT_GE(s.triangle, 0);
      const Triangle& t = g.triangles[s.triangle];
      const Vec2 c((i + 0.5) / size, (j + 0.5) / size);
      EXPECT_TRUE(test::contains(g.net, t, c));
      const Vec2 p =
          s.weight[0] * g.net[t[0]] + s.weight[1] * g.net[t[1]] + s.weight[2] * g.net[t[2]];
      EXPECT_LT((p - c).norm(), 1e-14);
      for (double w : s.weight) EXPECT_GE(w, -1e-14);
    }
}

}  // namespace
}  // namespace skinslide
