#include "mesh/measures.h"

#include <gtest/gtest.h>

namespace skinslide {
namespace {

TEST(Measures, BarLengthsAreEuclidean) {
  const Positions3 p{{0, 0, 0}, {3, 4, 0}, {3, 4, 12}};
  const auto l = bar_lengths(p, {{0, 1}, {1, 2}, {0, 2}});
  EXPECT_DOUBLE_EQ(l[0], 5);
  EXPECT_DOUBLE_EQ(l[1], 12);
  EXPECT_DOUBLE_EQ(l[2], 13);
}

TEST(Measures, ReversedCountsOnlyTheMinoritySignFlippedAlsoZeroArea) {
  // Three counter-clockwise triangles, one clockwise, one with zero area.
  const Positions2 p{{0, 0}, {1, 0}, {0, 1}, {1, 1}, {2, 0}, {3, 0}};
  const std::vector<Triangle> tris{{0, 1, 2}, {1, 3, 2}, {1, 4, 3}, {1, 2, 4}, {1, 4, 5}};
  const Folds f = count_folds(p, tris);
  EXPECT_EQ(f.reversed, std::vector<Index>{3});
  EXPECT_EQ(f.flipped, 2);
  EXPECT_EQ(flipped_triangles(p, tris), 2);
}

TEST(Measures, FlippedTrianglesCountsTheMinorityOrientation) {
  const Positions2 x{{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  EXPECT_EQ(flipped_triangles(x, {{0, 1, 2}, {1, 3, 2}}), 0);
  EXPECT_EQ(flipped_triangles(x, {{0, 1, 2}, {1, 3, 2}, {0, 2, 1}}), 1);
  EXPECT_EQ(flipped_triangles(x, {{0, 1, 2}, {0, 1, 1}}), 1);  // zero area counts
}

}  // namespace
}  // namespace skinslide
