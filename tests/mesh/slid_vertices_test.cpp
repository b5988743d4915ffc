#include "mesh/slid_vertices.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "helpers/meshes.h"

namespace skinslide {

TEST(Transfer, SurfacePointInterpolatesTheFanTriangle) {
  const PolyMesh mesh = test::quad_grid(1, 1);  // face 0 = (0, 1, 3, 2)
  Positions3 p = mesh.positions;
  p[3] = Vec3(1, 1, 2);
  // Fan triangle 1 of the quad: slots (0, 2, 3) = vertices (0, 3, 2).
  const SurfaceSample s{0, {0, 2, 3}, {0.25, 0.5, 0.25}};
  const Vec3 x = surface_point(mesh, p, s);
  EXPECT_DOUBLE_EQ(x.x(), 0.5);
  EXPECT_DOUBLE_EQ(x.y(), 0.75);
  EXPECT_DOUBLE_EQ(x.z(), 1.0);
}

TEST(Transfer, NonFiniteResultsAreNumericErrors) {
  const PolyMesh mesh = test::quad_grid(1, 1);
  Positions3 p = mesh.positions;
  p[1] = Vec3(INFINITY, 0, 0);
  EXPECT_THROW(surface_point(mesh, p, SurfaceSample{0, {0, 1, 2}, {0.2, 0.4, 0.4}}), Error);
}

TEST(Transfer, ApplySlideMovesOnlyTheListedVertices) {
  const Positions3 frame{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  SlidVertices slid;
  slid.vertex = {1};
  slid.sample = {SurfaceSample{}};
  slid.position = {Vec3(5, 5, 5)};
  const Positions3 out = apply_slide(frame, slid);
  EXPECT_EQ(out[0], frame[0]);
  EXPECT_EQ(out[1], Vec3(5, 5, 5));
  EXPECT_EQ(out[2], frame[2]);
}

}  // namespace skinslide
