#include "paper/square_boundary.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "mesh/outer_loop.h"

namespace skinslide {

SquareBoundary square_positions(const Positions3& p) {
  const Index n = static_cast<Index>(p.size());
  if (n < 4)
    throw Error(ErrorKind::Input, "the outer boundary loop has " + std::to_string(n) +
                                      " vertices; at least 4 are needed for the square's corners");
  std::vector<double> s(n + 1, 0.0);  // cumulative arc length; s[n] = L
  for (Index k = 0; k < n; ++k) s[k + 1] = s[k] + (p[(k + 1) % n] - p[k]).norm();
  const double total = s[n];
  if (!(total > 0) || !std::isfinite(total))
    throw Error(ErrorKind::Input, "the outer boundary loop has zero length");

  SquareBoundary out;
  out.corners[0] = 0;
  for (int j = 1; j < 4; ++j) {
    const double target = j * total / 4;
    double best = INFINITY;
    for (Index k = 0; k < n; ++k) best = std::min(best, std::abs(s[k] - target));
    // Uniformly sampled loops put j*L/4 exactly between two vertices; without a tolerance the
    // choice would flip with round-off and move the whole net.
    Index k = 0;
    while (std::abs(s[k] - target) > best + kTieRelative * total) ++k;
    k = std::max(k, out.corners[j - 1] + 1);
    k = std::min(k, n - 4 + j);
    out.corners[j] = k;
  }

  static const Vec2 kCorner[5] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}};
  out.positions.resize(n);
  for (int j = 0; j < 4; ++j) {
    const Index a = out.corners[j];
    const Index b = j < 3 ? out.corners[j + 1] : n;
    const double den = s[b] - s[a];
    for (Index k = a; k < b; ++k) {
      const double t = den > 0 ? (s[k] - s[a]) / den : 0.0;
      out.positions[k] = kCorner[j] + t * (kCorner[j + 1] - kCorner[j]);
    }
  }
  return out;
}

SquareBoundary square_positions(const Positions3& p, const std::array<Index, 4>& corners) {
  const Index n = static_cast<Index>(p.size());
  // Offsets from corner 0 along the walk must increase strictly: the corners go round the
  // square in the loop's own direction, so the net keeps the patch's orientation.
  std::array<Index, 4> offset{};
  for (int j = 0; j < 4; ++j) {
    if (corners[j] < 0 || corners[j] >= n)
      throw Error(ErrorKind::Input, "a corner is not on the outer loop");
    offset[j] = (corners[j] - corners[0] + n) % n;
  }
  for (int j = 1; j < 4; ++j)
    if (offset[j] <= offset[j - 1])
      throw Error(ErrorKind::Input,
                  "the corners are not four distinct vertices in the loop's walking order");
  std::vector<double> edge(n);
  for (Index k = 0; k < n; ++k) edge[k] = (p[(k + 1) % n] - p[k]).norm();

  static const Vec2 kCorner[5] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}};
  SquareBoundary out;
  out.corners = corners;
  out.positions.resize(n);
  for (int j = 0; j < 4; ++j) {
    const Index steps = (j < 3 ? offset[j + 1] : n) - offset[j];
    double side = 0;
    for (Index i = 0; i < steps; ++i) side += edge[(corners[j] + i) % n];
    if (!(side > 0) || !std::isfinite(side))
      throw Error(ErrorKind::Input, "the side from corner " + std::to_string(j) + " to corner " +
                                        std::to_string((j + 1) % 4) + " has zero length");
    double s = 0;
    for (Index i = 0; i < steps; ++i) {
      const Index k = (corners[j] + i) % n;
      out.positions[k] = kCorner[j] + (s / side) * (kCorner[j + 1] - kCorner[j]);
      s += edge[k];
    }
  }
  return out;
}

}  // namespace skinslide
