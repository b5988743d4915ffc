#include "dump/coverage.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"

namespace skinslide {
namespace {

using Polygon = std::vector<Vec2>;

// Sutherland-Hodgman against one axis-aligned half-plane: keeps the side where
// sign * (p[axis] - bound) >= 0. Convex in, convex out, so a triangle stays small (<= 7 points
// after four clips).
void clip(const Polygon& in, int axis, double bound, double sign, Polygon& out) {
  out.clear();
  const size_t n = in.size();
  for (size_t k = 0; k < n; ++k) {
    const Vec2& p = in[k];
    const Vec2& q = in[(k + 1) % n];
    const double dp = sign * (p[axis] - bound);
    const double dq = sign * (q[axis] - bound);
    if (dp >= 0) out.push_back(p);
    if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) {
      const double t = dp / (dp - dq);
      Vec2 x = p + t * (q - p);
      x[axis] = bound;  // exactly on the texel edge, so neighbouring texels share it
      out.push_back(x);
    }
  }
}

double area(const Polygon& poly) {
  double twice = 0;
  for (size_t k = 0, n = poly.size(); k < n; ++k) {
    const Vec2& p = poly[k];
    const Vec2& q = poly[(k + 1) % n];
    twice += p.x() * q.y() - p.y() * q.x();
  }
  return 0.5 * std::abs(twice);
}

}  // namespace

std::vector<float> coverage_image(const Positions2& net, const std::vector<Triangle>& triangles,
                                  int size) {
  SKINSLIDE_CHECK(size >= 1, "coverage image size");
  const size_t n = static_cast<size_t>(size);
  // Accumulate in double and in texel units (a texel has area 1), triangle by triangle in index
  // order: the sum, and so the bytes written, do not depend on anything but the inputs.
  std::vector<double> sum(n * n, 0.0);
  Polygon tri(3), row, cell, tmp;
  for (const Triangle& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      SKINSLIDE_CHECK(t[k] >= 0 && static_cast<size_t>(t[k]) < net.size(), "triangle index");
      tri[k] = net[t[k]] * static_cast<double>(size);
    }
    if (area(tri) == 0) continue;
    const double y_lo = std::min({tri[0].y(), tri[1].y(), tri[2].y()});
    const double y_hi = std::max({tri[0].y(), tri[1].y(), tri[2].y()});
    const int j0 = std::max(0, static_cast<int>(std::floor(y_lo)));
    const int j1 = std::min(size - 1, static_cast<int>(std::floor(y_hi)));
    for (int j = j0; j <= j1; ++j) {
      clip(tri, 1, j, +1, tmp);
      clip(tmp, 1, j + 1, -1, row);
      if (row.size() < 3) continue;
      double x_lo = row[0].x(), x_hi = row[0].x();
      for (const Vec2& p : row) {
        x_lo = std::min(x_lo, p.x());
        x_hi = std::max(x_hi, p.x());
      }
      const int i0 = std::max(0, static_cast<int>(std::floor(x_lo)));
      const int i1 = std::min(size - 1, static_cast<int>(std::floor(x_hi)));
      for (int i = i0; i <= i1; ++i) {
        clip(row, 0, i, +1, tmp);
        clip(tmp, 0, i + 1, -1, cell);
        if (cell.size() >= 3) sum[static_cast<size_t>(j) * n + i] += area(cell);
      }
    }
  }
  std::vector<float> coverage(n * n);
  for (size_t k = 0; k < n * n; ++k) coverage[k] = static_cast<float>(std::min(sum[k], 1.0));
  return coverage;
}

}  // namespace skinslide
