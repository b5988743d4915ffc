#include "dump/coverage.h"

#include <numeric>

#include <gtest/gtest.h>

#include "helpers/nets.h"

namespace skinslide {
namespace {

// Coverage is exact up to float storage: |sum(A)/size^2 - area| <= kAreaTol (dump/coverage.h).
constexpr double kAreaTol = 1e-7;

double mean(const std::vector<float>& a) {
  return std::accumulate(a.begin(), a.end(), 0.0) / static_cast<double>(a.size());
}

TEST(Coverage, SquareCoversEveryTexelFully) {
  const test::TestNet g = test::square_net();
  for (int size : {1, 7, 64}) {
    const std::vector<float> a = coverage_image(g.net, g.triangles, size);
    ASSERT_EQ(a.size(), size_t(size) * size);
    for (float x : a) EXPECT_NEAR(x, 1.0, 1e-6) << "size " << size;
  }
}

TEST(Coverage, HoleIsSubtractedAtAnyResolution) {
  const test::TestNet g = test::holed_net();
  for (int size : {3, 37, 64, 100, 256}) {
    const std::vector<float> a = coverage_image(g.net, g.triangles, size);
    EXPECT_NEAR(mean(a), g.area, kAreaTol) << "size " << size;
  }
  // 64/3 is not a whole number: the hole's edges cut texels, which are partly covered.
  const std::vector<float> a = coverage_image(g.net, g.triangles, 64);
  EXPECT_EQ(a[32 * 64 + 32], 0.0f);  // the centre texel is in the hole
  EXPECT_EQ(a[0], 1.0f);
  const float edge = a[32 * 64 + 21];  // the column holding u = 1/3
  EXPECT_GT(edge, 0.0f);
  EXPECT_LT(edge, 1.0f);
  EXPECT_NEAR(edge, 64.0 / 3 - 21, 1e-6);
}

TEST(Coverage, ArbitraryTriangleEitherOrientation) {
  const Positions2 net = {{0.1, 0.1}, {0.9, 0.2}, {0.3, 0.8}};
  const double area = 0.5 * std::abs((0.9 - 0.1) * (0.8 - 0.1) - (0.2 - 0.1) * (0.3 - 0.1));
  for (const Triangle& t : {Triangle{0, 1, 2}, Triangle{0, 2, 1}})
    EXPECT_NEAR(mean(coverage_image(net, {t}, 50)), area, kAreaTol);
}

TEST(Coverage, OnlyThePartInsideTheSquareCounts) {
  // (-0.5,0) (0.5,0) (0,1): its part with u >= 0 is (0,0) (0.5,0) (0,1), area 1/4.
  const Positions2 net = {{-0.5, 0}, {0.5, 0}, {0, 1}};
  EXPECT_NEAR(mean(coverage_image(net, {{0, 1, 2}}, 40)), 0.25, kAreaTol);
}

TEST(Coverage, OverlapIsClampedToOne) {
  const test::TestNet g = test::square_net();
  std::vector<Triangle> twice = g.triangles;
  twice.push_back(g.triangles[0]);
  const std::vector<float> a = coverage_image(g.net, twice, 16);
  for (float x : a) EXPECT_LE(x, 1.0f);
  EXPECT_NEAR(mean(a), 1.0, kAreaTol);
}

TEST(Coverage, DegenerateTriangleCoversNothing) {
  const Positions2 net = {{0.1, 0.1}, {0.5, 0.5}, {0.9, 0.9}};
  const std::vector<float> a = coverage_image(net, {{0, 1, 2}}, 16);
  EXPECT_EQ(mean(a), 0.0);
}

}  // namespace
}  // namespace skinslide
