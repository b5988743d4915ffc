#include "dump/preview.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"

namespace skinslide {
namespace {

using Color = std::array<std::uint8_t, 3>;

// Drawing happens in float on a canvas and is quantised to 8 bits once at the end, so
// overlapping strokes do not accumulate rounding.
class Canvas {
 public:
  Canvas(int size, const Color& background)
      : size_(size),
        margin_(size / 32.0),
        scale_(size - 2 * margin_),
        rgb_(static_cast<size_t>(size) * size * 3) {
    for (size_t k = 0; k < rgb_.size(); ++k) rgb_[k] = background[k % 3];
  }

  // Net (u, v) to continuous image coordinates: pixel (x, y) spans [x, x+1) x [y, y+1), v up.
  Vec2 to_image(const Vec2& uv) const {
    return {margin_ + uv.x() * scale_, margin_ + (1.0 - uv.y()) * scale_};
  }

  // A segment about one pixel wide: each pixel near it gets alpha = 1 - distance from its
  // centre to the segment. Walks the major axis so a pixel is visited once per segment.
  void line(const Vec2& a_uv, const Vec2& b_uv, const Color& color) {
    const Vec2 a = to_image(a_uv), b = to_image(b_uv);
    const Vec2 d = b - a;
    const double len2 = d.squaredNorm();
    if (!(len2 > 0) || !a.allFinite() || !b.allFinite()) return;
    const int major = std::abs(d.x()) >= std::abs(d.y()) ? 0 : 1;
    const int minor = 1 - major;
    const double lo = std::min(a[major], b[major]), hi = std::max(a[major], b[major]);
    const int m0 = std::max(0, static_cast<int>(std::floor(lo - 1)));
    const int m1 = std::min(size_ - 1, static_cast<int>(std::floor(hi + 1)));
    for (int m = m0; m <= m1; ++m) {
      const double c = m + 0.5;
      const double t = std::clamp((c - a[major]) / d[major], 0.0, 1.0);
      const double across = a[minor] + t * d[minor];
      const int n0 = std::max(0, static_cast<int>(std::floor(across - 1.5)));
      const int n1 = std::min(size_ - 1, static_cast<int>(std::floor(across + 1.5)));
      for (int n = n0; n <= n1; ++n) {
        Vec2 p;
        p[major] = c;
        p[minor] = n + 0.5;
        const double s = std::clamp((p - a).dot(d) / len2, 0.0, 1.0);
        const double dist = (a + s * d - p).norm();
        blend(major == 0 ? m : n, major == 0 ? n : m, color, 1.0 - dist);
      }
    }
  }

  void dot(const Vec2& uv, double radius, const Color& color) {
    const Vec2 c = to_image(uv);
    if (!c.allFinite()) return;
    const int x0 = std::max(0, static_cast<int>(std::floor(c.x() - radius - 1)));
    const int x1 = std::min(size_ - 1, static_cast<int>(std::floor(c.x() + radius + 1)));
    const int y0 = std::max(0, static_cast<int>(std::floor(c.y() - radius - 1)));
    const int y1 = std::min(size_ - 1, static_cast<int>(std::floor(c.y() + radius + 1)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        blend(x, y, color, radius + 0.5 - (Vec2(x + 0.5, y + 0.5) - c).norm());
  }

  RgbImage image() const {
    RgbImage out;
    out.width = out.height = size_;
    out.rgb.resize(rgb_.size());
    for (size_t k = 0; k < rgb_.size(); ++k)
      out.rgb[k] = static_cast<std::uint8_t>(std::lround(std::clamp(rgb_[k], 0.0f, 255.0f)));
    return out;
  }

 private:
  void blend(int x, int y, const Color& color, double alpha) {
    if (alpha <= 0) return;
    const float a = static_cast<float>(std::min(alpha, 1.0));
    float* p = &rgb_[(static_cast<size_t>(y) * size_ + x) * 3];
    for (int c = 0; c < 3; ++c) p[c] += a * (color[c] - p[c]);
  }

  int size_;
  double margin_;
  double scale_;
  std::vector<float> rgb_;
};

}  // namespace

RgbImage preview_image(const Positions2& bind_net, const Positions2& frame_net,
                       const std::vector<std::array<Index, 2>>& bars,
                       const std::vector<Index>& moved, int size, const PreviewColors& colors,
                       bool slides_to_frame_net) {
  SKINSLIDE_CHECK(size >= 16, "preview size");
  SKINSLIDE_CHECK(frame_net.size() == bind_net.size(), "bind and frame nets differ in size");
  auto valid = [&](Index v) { return v >= 0 && static_cast<size_t>(v) < bind_net.size(); };
  Canvas canvas(size, colors.background);
  const Vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int k = 0; k < 4; ++k) canvas.line(corners[k], corners[(k + 1) % 4], colors.square);
  for (const auto& bar : bars) {
    SKINSLIDE_CHECK(valid(bar[0]) && valid(bar[1]), "bar index");
    canvas.line(bind_net[bar[0]], bind_net[bar[1]], colors.bind);
  }
  for (const auto& bar : bars) canvas.line(frame_net[bar[0]], frame_net[bar[1]], colors.frame);
  // Dots grow with the image so they stay visible at 2048 and do not swamp a 256 preview.
  const double radius = std::max(1.0, size / 400.0);
  for (Index v : moved) {
    SKINSLIDE_CHECK(valid(v), "moved vertex index");
    canvas.line(frame_net[v], bind_net[v], colors.moved);
    canvas.dot(slides_to_frame_net ? frame_net[v] : bind_net[v], radius, colors.moved);
  }
  return canvas.image();
}

}  // namespace skinslide
