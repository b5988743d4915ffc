#include "locate/barycentric.h"

#include <algorithm>
#include <cmath>

namespace skinslide {
namespace {
// Closest point of segment [a, b] to p as the parameter t in [0,1] (a point for a == b).
double segment_t(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (!(len2 > 0)) return 0.0;
  return std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
}
}  // namespace

ClosestPoint closest_point(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  ClosestPoint best;
  const Barycentric inside = barycentric(p, a, b, c);
  if (inside.ok && inside.min() >= 0) {
    best.w = inside.w;
    best.distance2 = 0;
    return best;
  }
  // Outside (or degenerate): the closest point lies on one of the three edges.
  best.distance2 = INFINITY;
  const Vec2* corner[3] = {&a, &b, &c};
  for (int e = 0; e < 3; ++e) {
    const int i = e, j = (e + 1) % 3;
    const double t = segment_t(p, *corner[i], *corner[j]);
    const Vec2 q = (1 - t) * *corner[i] + t * *corner[j];
    const double d2 = (q - p).squaredNorm();
    if (d2 < best.distance2) {
      best.distance2 = d2;
      best.w = {0, 0, 0};
      best.w[i] = 1 - t;
      best.w[j] = t;
    }
  }
  return best;
}

}  // namespace skinslide
