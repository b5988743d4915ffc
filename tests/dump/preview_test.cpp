#include "dump/preview.h"

#include <gtest/gtest.h>

#include "helpers/nets.h"

namespace skinslide {
namespace {

using Rgb = std::array<std::uint8_t, 3>;

// How strongly the pixels around net point uv show `color` over the background: the largest
// alpha a, over the 3x3 pixels around uv (by the mapping preview_image() documents: a margin of
// size/32 pixels, v up), of a pixel that is background + a * (color - background) up to 8-bit
// rounding. 0 when none is such a blend.
double strength(const RgbImage& im, const Vec2& uv, const std::array<std::uint8_t, 3>& color) {
  const PreviewColors c;
  const Eigen::Vector3d bg(c.background[0], c.background[1], c.background[2]);
  const Eigen::Vector3d d = Eigen::Vector3d(color[0], color[1], color[2]) - bg;
  const double m = im.width / 32.0, s = im.width - 2 * m;
  const int x0 = int(std::floor(m + uv.x() * s));
  const int y0 = int(std::floor(m + (1 - uv.y()) * s));
  double best = 0;
  for (int y = y0 - 1; y <= y0 + 1; ++y)
    for (int x = x0 - 1; x <= x0 + 1; ++x) {
      const std::uint8_t* p = &im.rgb[(size_t(y) * im.width + x) * 3];
      const Eigen::Vector3d q = Eigen::Vector3d(p[0], p[1], p[2]) - bg;
      const double a = q.dot(d) / d.squaredNorm();
      if ((q - a * d).norm() <= 2.0) best = std::max(best, a);
    }
  return best;
}

// Whether the pixel around uv most like the frame's colour is nearer to it than to the bind's.
bool frame_on_top(const RgbImage& im, const Vec2& uv) {
  const PreviewColors c;
  auto dist = [](const std::uint8_t* p, const std::array<std::uint8_t, 3>& q) {
    return Eigen::Vector3d(p[0] - q[0], p[1] - q[1], p[2] - q[2]).norm();
  };
  const double m = im.width / 32.0, s = im.width - 2 * m;
  const int x0 = int(std::floor(m + uv.x() * s));
  const int y0 = int(std::floor(m + (1 - uv.y()) * s));
  const std::uint8_t* best = nullptr;
  for (int y = y0 - 1; y <= y0 + 1; ++y)
    for (int x = x0 - 1; x <= x0 + 1; ++x) {
      const std::uint8_t* p = &im.rgb[(size_t(y) * im.width + x) * 3];
      if (!best || dist(p, c.frame) < dist(best, c.frame)) best = p;
    }
  return dist(best, c.frame) < dist(best, c.bind) && dist(best, c.frame) < dist(best, c.background);
}

struct Scene {
  test::TestNet g = test::grid_net(2);
  Positions2 frame;
  Scene() {
    frame = g.net;
    frame[4] = Vec2(0.6, 0.3);  // the centre vertex moves right and down in the frame net
  }
  RgbImage draw(int size) const { return preview_image(g.net, frame, g.bars, {4}, size); }
};

TEST(Preview, ShapeAndDeterminism) {
  const Scene s;
  const RgbImage a = s.draw(256);
  EXPECT_EQ(a.width, 256);
  EXPECT_EQ(a.height, 256);
  EXPECT_EQ(a.rgb.size(), 256u * 256 * 3);
  EXPECT_EQ(a.rgb, s.draw(256).rgb);
}

TEST(Preview, EachNetInItsColourWithVUp) {
  const Scene s;
  const PreviewColors c;
  const RgbImage im = s.draw(512);
  EXPECT_EQ(strength(im, {0.25, 0.75}, c.bind), 0.0);  // inside a quad, away from every line
  EXPECT_EQ(strength(im, {0.25, 0.75}, c.frame), 0.0);
  EXPECT_EQ(strength(im, {-0.02, 0.5}, c.frame), 0.0);  // the margin
  // The bar from vertex 1 (0.5, 0) to the centre: in the bind at u = 0.5, in the frame through
  // (0.55, 0.15). A line one pixel wide on a pixel border shows as two pixels at alpha 1/2.
  EXPECT_GE(strength(im, {0.5, 0.15}, c.bind), 0.45);
  EXPECT_EQ(strength(im, {0.5, 0.15}, c.frame), 0.0);
  EXPECT_GE(strength(im, {0.55, 0.15}, c.frame), 0.45);
  EXPECT_EQ(strength(im, {0.55, 0.15}, c.bind), 0.0);
  // v is up: at the mirrored place the frame's bar from the centre to (0.5, 1) is at u ~ 0.52.
  EXPECT_EQ(strength(im, {0.55, 0.85}, c.frame), 0.0);
  // A bar the frame did not move: the frame is drawn over the bind (and the square's outline).
  EXPECT_TRUE(frame_on_top(im, {0.25, 0.0}));
  // The moved vertex: a dot at its bind position, and its slide segment from (0.6, 0.3).
  EXPECT_GE(strength(im, {0.5, 0.5}, c.moved), 0.99);
  EXPECT_GE(strength(im, {0.55, 0.4}, c.moved), 0.45);
}

TEST(Preview, IdentityFrameHidesTheBind) {
  const Scene s;
  const PreviewColors c;
  const RgbImage im = preview_image(s.g.net, s.g.net, s.g.bars, {}, 256);
  for (size_t k = 0; k < im.rgb.size(); k += 3) {
    const Rgb p{im.rgb[k], im.rgb[k + 1], im.rgb[k + 2]};
    // Every line pixel is the frame's colour blended over the bind's, never the bind's alone.
    EXPECT_NE(p, c.bind);
  }
}

}  // namespace
}  // namespace skinslide
