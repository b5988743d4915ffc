#include "paper/square_boundary.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"

namespace skinslide {
namespace {

Positions3 circle(int n) {
  Positions3 p;
  for (int k = 0; k < n; ++k)
    p.emplace_back(std::cos(2 * M_PI * k / n), std::sin(2 * M_PI * k / n), 0);
  return p;
}

TEST(SquareBoundary, EightEqualEdgesPutCornersEveryTwoVertices) {
  const SquareBoundary sq = square_positions(circle(8));
  EXPECT_EQ(sq.corners, (std::array<Index, 4>{0, 2, 4, 6}));
  const Vec2 expected[8] = {{0, 0}, {0.5, 0}, {1, 0}, {1, 0.5}, {1, 1}, {0.5, 1}, {0, 1}, {0, 0.5}};
  for (int k = 0; k < 8; ++k) {
    EXPECT_NEAR(sq.positions[k].x(), expected[k].x(), 1e-15) << k;
    EXPECT_NEAR(sq.positions[k].y(), expected[k].y(), 1e-15) << k;
  }
}

TEST(SquareBoundary, NearTiesGoToTheEarlierVertex) {
  // 10 equal edges: L/4 = 2.5 edges lies exactly between vertices 2 and 3 (round-off aside).
  const SquareBoundary sq = square_positions(circle(10));
  EXPECT_EQ(sq.corners, (std::array<Index, 4>{0, 2, 5, 7}));
}

TEST(SquareBoundary, SidesAreSpacedByArcLength) {
  // A rectangle 3 x 1 sampled at 1: corners at the start, 1/4, 1/2, 3/4 of the length 8.
  const Positions3 p{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0},
                     {3, 1, 0}, {2, 1, 0}, {1, 1, 0}, {0, 1, 0}};
  const SquareBoundary sq = square_positions(p);
  EXPECT_EQ(sq.corners, (std::array<Index, 4>{0, 2, 4, 6}));
  EXPECT_NEAR(sq.positions[3].y(), 0.5, 1e-15);  // vertex 3 halfway up side 1 (2 -> 4)
}

TEST(SquareBoundary, RejectsShortLoops) { EXPECT_THROW(square_positions(circle(3)), Error); }

}  // namespace
}  // namespace skinslide
