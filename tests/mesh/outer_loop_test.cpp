#include "mesh/outer_loop.h"

#include <gtest/gtest.h>

namespace skinslide {
namespace {

TEST(OuterLoop, OuterLoopIsTheLongestAndTiesGoToTheSmallestStart) {
  EXPECT_EQ(outer_loop({1.0, 3.0, 2.0}, {0, 5, 9}), 1);
  EXPECT_EQ(outer_loop({3.0, 3.0 * (1 - 1e-12)}, {7, 4}), 1);
  EXPECT_EQ(outer_loop({3.0, 3.0 * (1 - 1e-6)}, {7, 4}), 0);
}

TEST(OuterLoop, LoopLengthClosesTheLoop) {
  // A 3-4-5 right triangle: the closing edge (back to the first point) counts.
  EXPECT_DOUBLE_EQ(loop_length({{0, 0, 0}, {3, 0, 0}, {3, 4, 0}}), 12.0);
}

}  // namespace
}  // namespace skinslide
