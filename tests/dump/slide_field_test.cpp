#include "dump/slide_field.h"

#include <gtest/gtest.h>

#include "helpers/nets.h"

namespace skinslide {
namespace {

TEST(SlideField, IdentityFrameIsZero) {
  const test::TestNet g = test::grid_net(3);
  const SlideField f = slide_field(g.net, g.net, g.triangles, 24);
  ASSERT_EQ(f.size, 24);
  for (size_t k = 0; k < f.x.size(); ++k) {
    EXPECT_NEAR(f.x[k], 0.0f, 1e-7);
    EXPECT_NEAR(f.y[k], 0.0f, 1e-7);
  }
}

TEST(SlideField, AffineFrameGivesTheAffineDisplacement) {
  const test::TestNet g = test::grid_net(2);
  Eigen::Matrix2d M;
  M << 0.8, 0.1, -0.2, 0.9;
  const Vec2 t(0.05, 0.1);
  Positions2 frame;
  for (const Vec2& u : g.net) frame.push_back(M * u + t);
  const int size = 16;
  const SlideField f = slide_field(g.net, frame, g.triangles, size);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const Vec2 u((i + 0.5) / size, (j + 0.5) / size);
      const Vec2 want = M * u + t - u;  // sign: frame point minus texel centre
      const size_t k = size_t(j) * size + i;
      EXPECT_NEAR(f.x[k], want.x(), 1e-6);
      EXPECT_NEAR(f.y[k], want.y(), 1e-6);
    }
}

TEST(SlideField, MovedVertexShowsItsMoveAtItsTexel) {
  // 3x3 texels: the centre texel's centre is the grid's centre vertex (id 4) exactly.
  const test::TestNet g = test::grid_net(2);
  Positions2 frame = g.net;
  frame[4] += Vec2(0.1, -0.05);
  const SlideField f = slide_field(g.net, frame, g.triangles, 3);
  EXPECT_NEAR(f.x[4], 0.1, 1e-7);
  EXPECT_NEAR(f.y[4], -0.05, 1e-7);
  // Corner texel centres (1/6, 1/6) and (5/6, 5/6) lie on the diagonals of quads whose split
  // runs through vertex 4, where its weight is 1/3; (5/6, 1/6) and (1/6, 5/6) lie in triangles
  // without it.
  for (int k : {0, 8}) {
    EXPECT_NEAR(f.x[k], 0.1 / 3, 1e-7);
    EXPECT_NEAR(f.y[k], -0.05 / 3, 1e-7);
  }
  for (int k : {2, 6}) {
    EXPECT_NEAR(f.x[k], 0.0, 1e-7);
    EXPECT_NEAR(f.y[k], 0.0, 1e-7);
  }
}

TEST(SlideField, HoleIsZero) {
  const test::TestNet g = test::holed_net();
  Positions2 frame = g.net;
  for (Vec2& p : frame) p += Vec2(0.01, 0.02);  // a shift, so covered texels are non-zero
  const int size = 30;
  const SlideField f = slide_field(g.net, frame, g.triangles, size);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const bool hole = i >= 10 && i < 20 && j >= 10 && j < 20;
      const size_t k = size_t(j) * size + i;
      EXPECT_NEAR(f.x[k], hole ? 0.0 : 0.01, 1e-7);
      EXPECT_NEAR(f.y[k], hole ? 0.0 : 0.02, 1e-7);
    }
}

}  // namespace
}  // namespace skinslide
