// Hand-built 2D nets (with 3D positions) for the dump and image tests.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Dense>

#include "core/types.h"
#include "locate/id_raster.h"

namespace skinslide::test {

struct TestNet {
  Positions2 net;
  std::vector<Triangle> triangles;
  std::vector<std::array<Index, 2>> bars;  ///< polygon edges (the quads' sides), a < b
  std::vector<Index> interior;             ///< vertices on no boundary
  double area = 0;                         ///< exact area: unit square minus holes
};

/// The unit square as an n x n grid of quads, each split into two triangles: (n+1)^2 vertices,
/// vertex (a, b) = id b*(n+1) + a at (a/n, b/n). `skip` (if >= 0) is a quad left out: a hole.
inline TestNet grid_net(int n, int skip_a = -1, int skip_b = -1) {
  TestNet g;
  const int m = n + 1;
  for (int b = 0; b <= n; ++b)
    for (int a = 0; a <= n; ++a) g.net.emplace_back(double(a) / n, double(b) / n);
  auto id = [m](int a, int b) { return Index(b * m + a); };
  auto add_bar = [&g](Index p, Index q) {
    std::array<Index, 2> bar{std::min(p, q), std::max(p, q)};
    for (const auto& e : g.bars)
      if (e == bar) return;
    g.bars.push_back(bar);
  };
  for (int b = 0; b < n; ++b)
    for (int a = 0; a < n; ++a) {
      if (a == skip_a && b == skip_b) continue;
      const Index q[4] = {id(a, b), id(a + 1, b), id(a + 1, b + 1), id(a, b + 1)};
      g.triangles.push_back({q[0], q[1], q[2]});
      g.triangles.push_back({q[0], q[2], q[3]});
      for (int k = 0; k < 4; ++k) add_bar(q[k], q[(k + 1) % 4]);
    }
  for (int b = 1; b < n; ++b)
    for (int a = 1; a < n; ++a) {
      const bool on_hole = (a == skip_a || a == skip_a + 1) && (b == skip_b || b == skip_b + 1);
      if (!on_hole) g.interior.push_back(id(a, b));
    }
  g.area = skip_a >= 0 ? 1.0 - 1.0 / (n * n) : 1.0;
  return g;
}

/// The unit square split into two triangles.
inline TestNet square_net() { return grid_net(1); }

/// A 3x3 grid with its centre quad missing: a square hole of area 1/9.
inline TestNet holed_net() { return grid_net(3, 1, 1); }

/// 3D positions of a net bent like an elbow: the half u > 0.5 turns up by 60 degrees about the
/// line u = 0.5, and everything is scaled by 2 (mesh units).
inline Positions3 bent(const Positions2& net) {
  Positions3 p;
  const double c = std::cos(std::numbers::pi / 3), s = std::sin(std::numbers::pi / 3);
  for (const Vec2& uv : net) {
    const double u = uv.x(), v = uv.y();
    if (u <= 0.5)
      p.emplace_back(2 * u, 2 * v, 0.0);
    else
      p.emplace_back(2 * (0.5 + (u - 0.5) * c), 2 * v, 2 * (u - 0.5) * s);
  }
  return p;
}

/// Largest stretch of the piecewise-linear map net -> points: the largest singular value of any
/// triangle's 3x2 Jacobian. |P(x) - P(y)| <= this * |x - y| for x, y in one triangle.
inline double max_stretch(const Positions2& net, const std::vector<Triangle>& triangles,
                          const Positions3& points) {
  double worst = 0;
  for (const Triangle& t : triangles) {
    Eigen::Matrix2d D;
    D.col(0) = net[t[1]] - net[t[0]];
    D.col(1) = net[t[2]] - net[t[0]];
    Eigen::Matrix<double, 3, 2> E;
    E.col(0) = points[t[1]] - points[t[0]];
    E.col(1) = points[t[2]] - points[t[0]];
    const Eigen::Matrix<double, 3, 2> J = E * D.inverse();
    Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>> svd(J);
    worst = std::max(worst, svd.singularValues()(0));
  }
  return worst;
}

/// True when point p lies in triangle t of `net` (edges inclusive, up to eps).
inline bool contains(const Positions2& net, const Triangle& t, const Vec2& p, double eps = 1e-12) {
  auto cross = [](const Vec2& a, const Vec2& b, const Vec2& c) {
    return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  };
  const double s = cross(net[t[0]], net[t[1]], net[t[2]]) > 0 ? 1 : -1;
  return s * cross(net[t[0]], net[t[1]], p) >= -eps && s * cross(net[t[1]], net[t[2]], p) >= -eps &&
         s * cross(net[t[2]], net[t[0]], p) >= -eps;
}

}  // namespace skinslide::test
