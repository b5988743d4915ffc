#include "paper/force_density.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace skinslide {

TEST(ForceDensity, PaperIsOneMinusRelativeLengthWithAFloor) {
  const auto q = force_densities({1.0, 2.0, 4.0}, Density::Paper, 1e-3);
  ASSERT_EQ(q.size(), 3u);
  EXPECT_DOUBLE_EQ(q[0], 0.75);
  EXPECT_DOUBLE_EQ(q[1], 0.5);
  EXPECT_DOUBLE_EQ(q[2], 1e-3);  // the longest bar sits on the floor, not at 0
}

TEST(ForceDensity, InverseIsShortestOverLength) {
  const auto q = force_densities({1.0, 2.0, 4.0}, Density::Inverse, 1e-3);
  EXPECT_DOUBLE_EQ(q[0], 1.0);
  EXPECT_DOUBLE_EQ(q[1], 0.5);
  EXPECT_DOUBLE_EQ(q[2], 0.25);
  const auto floored = force_densities({1.0, 5000.0}, Density::Inverse, 1e-3);
  EXPECT_DOUBLE_EQ(floored[1], 1e-3);
}

TEST(ForceDensity, InverseStaysFiniteOnACollapsedBar) {
  const auto q = force_densities({0.0, 1.0}, Density::Inverse, 1e-3);
  EXPECT_DOUBLE_EQ(q[0], 1.0);
  EXPECT_DOUBLE_EQ(q[1], 1e-3);  // 1e-12 / 1 floored
}

TEST(ForceDensity, UniformIsOne) {
  for (double q : force_densities({0.5, 3.0}, Density::Uniform, 1e-3)) EXPECT_EQ(q, 1.0);
}

TEST(ForceDensity, AllZeroLengthsIsAnInputError) {
  EXPECT_THROW(force_densities({0.0, 0.0}, Density::Paper, 1e-3), Error);
}

}  // namespace skinslide
