#include "locate/locate.h"

#include <random>

#include <gtest/gtest.h>

#include "locate/barycentric.h"

namespace skinslide {
namespace {

// A jittered n x n grid net over the unit square, two triangles per cell.
struct Net {
  Positions2 points;
  std::vector<Triangle> triangles;
};
Net grid(int n, double jitter, unsigned seed) {
  Net net;
  std::mt19937 rng{seed};
  std::uniform_real_distribution<double> u(-jitter / n, jitter / n);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      Vec2 p(double(i) / n, double(j) / n);
      if (i > 0 && j > 0 && i < n && j < n) p += Vec2(u(rng), u(rng));
      net.points.push_back(p);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Index a = j * (n + 1) + i;
      net.triangles.push_back({a, a + 1, a + n + 2});
      net.triangles.push_back({a, a + n + 2, a + n + 1});
    }
  return net;
}

TEST(Locate, EveryPointIsFoundInATriangleThatHoldsIt) {
  const Net net = grid(20, 0.3, 0);
  const IdImage img = id_raster(net.points, net.triangles, 64);
  std::mt19937 rng{1};
  std::uniform_real_distribution<double> u(0, 1);
  Positions2 pts;
  for (int k = 0; k < 2000; ++k) pts.emplace_back(u(rng), u(rng));
  const auto loc = locate_points(pts, net.points, net.triangles, img);
  int fallbacks = 0;
  for (size_t k = 0; k < pts.size(); ++k) {
    const Triangle& t = net.triangles[loc[k].triangle];
    const Barycentric w = barycentric(pts[k], net.points[t[0]], net.points[t[1]], net.points[t[2]]);
    fallbacks += loc[k].fallback;
    EXPECT_GE(w.min(), -kInsideEps) << k;
    EXPECT_NEAR((loc[k].weight[0] * net.points[t[0]] + loc[k].weight[1] * net.points[t[1]] +
                 loc[k].weight[2] * net.points[t[2]] - pts[k]).norm(), 0, 1e-14);
  }
  // Cells are 3.2 px wide: only slivers that cover no pixel centre near the point need the fallback.
  EXPECT_LE(fallbacks, 20);
}

TEST(Locate, APointOnASharedEdgeGoesToTheLargerSmallestBarycentricThenLowerIndex) {
  const Positions2 net{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<Triangle> tris{{0, 1, 2}, {0, 2, 3}};
  const IdImage img = id_raster(net, tris, 16);
  const auto loc = locate_points({{0.5, 0.5}, {0.25, 0.25}}, net, tris, img);
  EXPECT_EQ(loc[0].triangle, 0);  // on the diagonal: both have min 0, the lower index wins
  EXPECT_EQ(loc[1].triangle, 0);
}

TEST(Locate, TrianglesSmallerThanAPixelAreFoundByTheFallback) {
  const Net net = grid(50, 0.2, 3);
  const IdImage img = id_raster(net.points, net.triangles, 8);  // 8 px for 5000 triangles
  std::mt19937 rng{2};
  std::uniform_real_distribution<double> u(0, 1);
  Positions2 pts;
  for (int k = 0; k < 500; ++k) pts.emplace_back(u(rng), u(rng));
  const auto loc = locate_points(pts, net.points, net.triangles, img);
  int fallbacks = 0;
  for (size_t k = 0; k < pts.size(); ++k) {
    const Triangle& t = net.triangles[loc[k].triangle];
    EXPECT_GE(barycentric(pts[k], net.points[t[0]], net.points[t[1]], net.points[t[2]]).min(),
              -kInsideEps);
    fallbacks += loc[k].fallback;
  }
  EXPECT_GT(fallbacks, 0);
}

TEST(Locate, APointOutsideTheNetTakesTheNearestTriangleClamped) {
  const Positions2 net{{0, 0}, {0.5, 0}, {0, 0.5}, {0.9, 0.9}, {1, 0.9}, {0.9, 1}};
  const std::vector<Triangle> tris{{0, 1, 2}, {3, 4, 5}};
  const IdImage img = id_raster(net, tris, 32);
  const auto loc = locate_points({{0.6, 0.1}, {0.99, 0.99}}, net, tris, img);
  EXPECT_TRUE(loc[0].fallback);
  EXPECT_EQ(loc[0].triangle, 0);
  for (double w : loc[0].weight) {
    EXPECT_GE(w, 0.0);
    EXPECT_LE(w, 1.0);
  }
  EXPECT_NEAR(loc[0].weight[1], 1.0, 1e-15);  // the closest point is corner (0.5, 0)
  EXPECT_EQ(loc[1].triangle, 1);
}

TEST(Locate, ClosestPointOnADegenerateTriangleIsFinite) {
  const ClosestPoint cp = closest_point({1, 1}, {0, 0}, {0, 0}, {0, 0});
  EXPECT_DOUBLE_EQ(cp.distance2, 2.0);
  EXPECT_DOUBLE_EQ(cp.w[0] + cp.w[1] + cp.w[2], 1.0);
}

}  // namespace
}  // namespace skinslide
