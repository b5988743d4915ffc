#include "mesh/measures.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"

namespace skinslide {
namespace {

// What require_computable_span refuses `points` (vertices 7, 8, 9) with, as an input error; ""
// when it accepts them.
std::string refusal(const Positions3& points) {
  try {
    require_computable_span(points, {7, 8, 9});
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    return e.what();
  }
  return "";
}

// Lengths' squares overflow near 1e154 and the elastic energy near 1e77: such a patch is refused
// naming its vertex of the largest coordinate, not left to fail later as "zero length".
TEST(Measures, APatchTooLargeForDoublesIsRefusedNamingAVertex) {
  EXPECT_EQ(refusal({Vec3(0, 0, 0), Vec3(1e59, 0, 0), Vec3(0, 1e59, 0)}), "");
  EXPECT_EQ(refusal({Vec3(0, 0, 0), Vec3(1e300, 0, 0), Vec3(0, -3e300, 0)}),
            "vertex 9 at (0, -3e+300, 0): coordinates too large: the patch spans 3.162e+300, "
            "and its lengths' squares and products overflow a double beyond a span of 1e+60; "
            "scale the mesh down");
}

// Under a span of 1e-30 float32 (the at-rest comparison, caches) loses precision and lengths'
// squares underflow further down (they read as "zero length" once): refused naming the vertex of
// the largest coordinate. Millimetres in kilometres (1e-6) are fine, and so is a patch on one
// point (span 0), which the methods handle as a degenerate frame.
TEST(Measures, APatchTooSmallForDoublesIsRefusedNamingAVertex) {
  EXPECT_EQ(refusal({Vec3(0, 0, 0), Vec3(1e-6, 0, 0), Vec3(0, 1e-6, 0)}), "");
  EXPECT_EQ(refusal({Vec3(0, 0, 0), Vec3(1e-30, 0, 0), Vec3(0, 1e-30, 0)}), "");
  EXPECT_EQ(refusal({Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)}), "");
  EXPECT_EQ(refusal({Vec3(0, 0, 0), Vec3(1e-300, 0, 0), Vec3(0, -3e-300, 0)}),
            "vertex 9 at (0, -3e-300, 0): coordinates too small: the patch spans 3.162e-300, "
            "under the smallest span of 1e-30 (frames are compared with the bind, and caches "
            "hold positions, in float32, which loses precision under 1e-38; lengths' squares "
            "underflow a double further down); scale the mesh up");
}

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

TEST(Measures, TurnedAgainstReadsTheNormalsDirectionWhateverTheirSize) {
  // A bind with rows of zero-area triangles had one whose normal is 2.5e-311 (a denormal): its
  // own product with itself underflowed to 0 and read a triangle left in place as turned.
  const Vec3 tiny{-0.0, 2.5e-311, 0.0};
  EXPECT_EQ(tiny.dot(tiny), 0.0);
  EXPECT_FALSE(turned_against(tiny, tiny));
  EXPECT_TRUE(turned_against(-tiny, tiny));
  EXPECT_FALSE(turned_against({0, 0, 1}, {0, 1e-300, 1e-300}));
  EXPECT_TRUE(turned_against({0, 0, 0}, {0, 0, 1}));    // collapsed: not along it
  EXPECT_TRUE(turned_against({1, 0, 0}, {0, 0, 1}));    // at a right angle
  EXPECT_FALSE(turned_against({0, 0, -1}, {0, 0, 0}));  // no frame area: nothing to turn from
  EXPECT_TRUE(turned_against({NAN, 0, 1}, {0, 0, 1}));
}

}  // namespace
}  // namespace skinslide
