// Barycentric coordinates in 2D triangles (Yang & Zhang 2010, section III.F: the area test).
#pragma once

#include <array>
#include <cmath>

#include "core/types.h"

namespace skinslide {

/// Barycentric tolerance: a point is inside a triangle when every coordinate is >= -kInsideEps.
constexpr double kInsideEps = 1e-12;

/// (a, b, c) = (Area(PBC), Area(APC), Area(ABP)) / Area(ABC), signed, so a + b + c = 1 and the
/// point is inside exactly when all three are >= 0. `ok` is false for a zero-area triangle.
struct Barycentric {
  std::array<double, 3> w{0, 0, 0};
  bool ok = false;
  double min() const { return std::min(w[0], std::min(w[1], w[2])); }
};
/// Inline: a walk through a frame net computes one per step.
inline Barycentric barycentric(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  const auto cross = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
  Barycentric out;
  const Vec2 e1 = b - a, e2 = c - a, d = p - a;
  const double area2 = cross(e1, e2);
  if (area2 == 0 || !std::isfinite(area2)) return out;
  const double wb = cross(d, e2) / area2;  // Area(APC) / Area(ABC)
  const double wc = cross(e1, d) / area2;  // Area(ABP) / Area(ABC)
  out.w = {1.0 - wb - wc, wb, wc};
  out.ok = std::isfinite(wb) && std::isfinite(wc);
  return out;
}

/// Barycentrics (each in [0,1], summing to 1) of the point of triangle ABC closest to p, and the
/// squared distance to it. Degenerate triangles fall back to their closest edge or corner.
struct ClosestPoint {
  std::array<double, 3> w{1, 0, 0};
  double distance2 = 0;
};
ClosestPoint closest_point(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c);

}  // namespace skinslide
