#include "compare/mesh_difference.h"

#include <gtest/gtest.h>

#include <cmath>

#include "helpers/meshes.h"

namespace skinslide {
namespace {

// One triangle (0,0,0) (1,0,0) (0,1,0): facing +z.
PolyMesh one_triangle() {
  PolyMesh m;
  m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  m.add_face({0, 1, 2});
  return m;
}

TEST(BoundingBoxDiagonal, IsTheBoxsDiagonal) {
  EXPECT_DOUBLE_EQ(bounding_box_diagonal(test::quad_grid(3, 4).positions), 5.0);
  EXPECT_EQ(bounding_box_diagonal({}), 0.0);
  EXPECT_EQ(bounding_box_diagonal({Vec3(1, 2, 3)}), 0.0);
}

TEST(FrameDifference, IdenticalFramesDoNotDiffer) {
  const PolyMesh grid = test::quad_grid(3, 4);
  const FrameDifference d = frame_difference(grid.positions, grid.positions, grid, 5.0, 0.0);
  EXPECT_EQ(d.max_distance, 0.0);
  EXPECT_EQ(d.vertex, -1);
  EXPECT_EQ(d.turned_faces, 0);
  EXPECT_EQ(d.first_turned_face, -1);
  EXPECT_FALSE(differs(d, 0.0));  // the same, even at tolerance 0
}

TEST(FrameDifference, TheFarthestVertexInDiagonals) {
  const PolyMesh grid = test::quad_grid(3, 4);  // diagonal 5
  Positions3 b = grid.positions;
  b[7] += Vec3(0, 0, 0.1);
  b[11] += Vec3(0, 0, -0.5);  // 0.5 away: the farthest
  b[12] += Vec3(0.5, 0, 0);   // as far, but after it
  const FrameDifference d = frame_difference(grid.positions, b, grid, 5.0, 1e-6);
  EXPECT_DOUBLE_EQ(d.max_distance, 0.1);  // 0.5 / 5
  EXPECT_EQ(d.vertex, 11);
  EXPECT_EQ(d.turned_faces, 0);
  EXPECT_TRUE(differs(d, 1e-6));
  EXPECT_FALSE(differs(d, 0.1));  // at the tolerance is within it
  EXPECT_TRUE(differs(d, 0.0999));
}

TEST(FrameDifference, AFaceTurnedOverCountsEvenWhenCloseByTheTolerance) {
  const PolyMesh tri = one_triangle();
  Positions3 b = tri.positions;
  b[2] = Vec3(0, -1, 0);  // across the opposite edge: facing -z
  const FrameDifference d = frame_difference(tri.positions, b, tri, std::sqrt(2.0), 1e-6);
  EXPECT_EQ(d.turned_faces, 1);
  EXPECT_EQ(d.first_turned_face, 0);
  EXPECT_EQ(d.vertex, 2);
  EXPECT_TRUE(differs(d, 10.0));  // a turned face differs whatever the distance tolerance
}

TEST(FrameDifference, ASliverThinnerThanTheToleranceHasNoOrientation) {
  // A needle 1e-9 high turned over by moving its apex 2e-9: within a tolerance of 1e-6.
  PolyMesh needle;
  needle.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 1e-9, 0)};
  needle.add_face({0, 1, 2});
  Positions3 b = needle.positions;
  b[2].y() = -1e-9;
  const FrameDifference d = frame_difference(needle.positions, b, needle, 1.0, 1e-6);
  EXPECT_EQ(d.turned_faces, 0);
  EXPECT_FALSE(differs(d, 1e-6));
  // At a tolerance below its height it is a face like any other.
  EXPECT_EQ(frame_difference(needle.positions, b, needle, 1.0, 1e-10).turned_faces, 1);
}

TEST(FrameDifference, QuadsFarFromTheOriginKeepTheirOrientationUnderALastBitChange) {
  PolyMesh grid = test::quad_grid(4, 4);
  for (Vec3& p : grid.positions) p += Vec3(1e6, -2e6, 3e6);
  Positions3 b = grid.positions;
  for (Vec3& p : b) p.x() = std::nextafter(p.x(), 1e9);  // each x one bit up
  const FrameDifference d = frame_difference(grid.positions, b, grid, std::sqrt(32.0), 1e-6);
  EXPECT_EQ(d.turned_faces, 0);
  EXPECT_GT(d.max_distance, 0.0);
  EXPECT_LT(d.max_distance, 1e-10);
  EXPECT_FALSE(differs(d, kDefaultCompareTolerance));
}

TEST(FrameDifference, WithoutFacesOnlyDistancesCount) {
  const PolyMesh tri = one_triangle();
  Positions3 b = tri.positions;
  b[2] = Vec3(0, -1, 0);
  const FrameDifference d = frame_difference(tri.positions, b, PolyMesh{}, 1.0, 1e-6);
  EXPECT_EQ(d.turned_faces, 0);
  EXPECT_DOUBLE_EQ(d.max_distance, 2.0);
}

TEST(FrameDifference, AFloat32LastBitIsFarBelowTheDefaultTolerance) {
  // data/elbow's size: coordinates up to 8, diagonal about 8.5; one float32 ulp at 8 is 9.5e-7,
  // 1.1e-7 of the diagonal.
  const PolyMesh grid = test::quad_grid(8, 1);
  Positions3 b = grid.positions;
  b[8].x() = std::nextafter(static_cast<float>(b[8].x()), 100.0f);
  const double diagonal = bounding_box_diagonal(grid.positions);
  const FrameDifference d = frame_difference(grid.positions, b, grid, diagonal, 1e-6);
  EXPECT_NEAR(d.max_distance, 9.5367431640625e-07 / diagonal, 1e-20);
  EXPECT_FALSE(differs(d, kDefaultCompareTolerance));
}

}  // namespace
}  // namespace skinslide
