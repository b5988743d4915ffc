#include "elastic/stationarity.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace skinslide {
namespace {

// A barycentric at most this small puts the point on the edge opposite that corner (two of them:
// on the third corner's node). The measure is then an epsilon-stationarity: a vertex that
// zig-zags across a ridge within a thousandth of a triangle's height is taken as on the ridge.
constexpr double kOnEdge = 1e-3;
// A frame facet whose doubled area is at most this share of its squared edges has no plane.
constexpr double kFlat = 1e-12;

// The directions a point can leave in across one facet: the facet's plane, cut to the side of
// `inward[k]` for each of its `cuts` bounding lines, whose edges are the `ray`s.
struct Sector {
  Vec3 normal;
  int cuts = 0;
  std::array<Vec3, 2> inward;
  std::array<Vec3, 4> ray;
  int rays = 0;
};

// The steepest way down found so far: the least g . w over unit w, and that w.
struct Lowest {
  double slope = 0;
  Vec3 direction = Vec3::Zero();
  void offer(double s, const Vec3& w) {
    if (s < slope) {
      slope = s;
      direction = w;
    }
  }
};

// Offers the least g . w over unit w in the sector.
void lowest_slope(const Sector& s, const Vec3& g, Lowest& lowest) {
  const Vec3 n = s.normal.normalized();
  const Vec3 h = g - n * n.dot(g);
  if (h.norm() > 0) {
    const Vec3 w = -h / h.norm();
    bool inside = true;
    for (int k = 0; k < s.cuts; ++k) inside = inside && w.dot(s.inward[k]) >= 0;
    if (inside) return lowest.offer(-h.norm(), w);
  }
  for (int k = 0; k < s.rays; ++k)
    if (s.ray[k].norm() > 0) lowest.offer(g.dot(s.ray[k]) / s.ray[k].norm(), s.ray[k].normalized());
}

bool flat(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a;
  return !(e1.cross(e2).norm() > kFlat * (e1.squaredNorm() + e2.squaredNorm()));
}

// The wedge at corner `k` of patch triangle t: between its two edges from that corner.
bool corner_sector(const FrameSurface& surface, Index t, int k, Sector& out) {
  const Triangle& tri = surface.chart.triangles[t];
  const Vec3 &p = surface.frame[tri[k]], &b = surface.frame[tri[(k + 1) % 3]],
             &c = surface.frame[tri[(k + 2) % 3]];
  if (flat(p, b, c)) return false;
  out.normal = (b - p).cross(c - p);
  out.ray = {b - p, c - p, Vec3::Zero(), Vec3::Zero()};
  out.rays = 2;
  out.inward = {out.normal.cross(b - p), (c - p).cross(out.normal)};
  out.cuts = 2;
  return true;
}

// The half of patch triangle t's plane on its side of the edge opposite corner k.
bool edge_sector(const FrameSurface& surface, Index t, int k, Sector& out) {
  const Triangle& tri = surface.chart.triangles[t];
  const Vec3 &p = surface.frame[tri[k]], &a = surface.frame[tri[(k + 1) % 3]],
             &b = surface.frame[tri[(k + 2) % 3]];
  if (flat(p, a, b)) return false;
  out.normal = (a - p).cross(b - p);
  out.ray = {b - a, a - b, Vec3::Zero(), Vec3::Zero()};
  out.rays = 2;
  out.inward[0] = out.normal.cross(b - a);  // from edge a->b towards p (counter-clockwise)
  out.cuts = 1;
  return true;
}

}  // namespace

Vec3 steepest_descent(const FrameSurface& surface, Index node, const ChartPoint& where,
                      const Vec3& g) {
  const Chart& chart = surface.chart;
  const Index t = where.triangle;
  int small = 0, corner = -1, edge = -1;
  for (int k = 0; k < 3; ++k)
    if (where.weight[k] <= kOnEdge) {
      ++small;
      edge = k;
    } else {
      corner = k;
    }
  if (node < 0 && small >= 2) node = chart.triangles[t][corner];
  Lowest lowest;
  Sector s;
  if (node >= 0) {
    for (Index c = chart.corner_start[node]; c < chart.corner_start[node + 1]; ++c) {
      const Index u = chart.corner_triangles[c];
      const Triangle& tri = chart.triangles[u];
      const int k = tri[0] == node ? 0 : tri[1] == node ? 1 : 2;
      if (corner_sector(surface, u, k, s)) lowest_slope(s, g, lowest);
    }
    return -lowest.slope * lowest.direction;
  }
  if (small == 0) {
    const Triangle& tri = chart.triangles[t];
    const Vec3 &a = surface.frame[tri[0]], &b = surface.frame[tri[1]], &c = surface.frame[tri[2]];
    if (flat(a, b, c)) return Vec3::Zero();
    s.normal = (b - a).cross(c - a);
    lowest_slope(s, g, lowest);
    return -lowest.slope * lowest.direction;
  }
  if (edge_sector(surface, t, edge, s)) lowest_slope(s, g, lowest);
  const Index across = chart.neighbour[t][edge];
  if (across >= 0 && across < chart.patch_triangle_count) {
    const Triangle& o = chart.triangles[across];
    const Index a = chart.triangles[t][(edge + 1) % 3];
    const Index b = chart.triangles[t][(edge + 2) % 3];
    for (int k = 0; k < 3; ++k)
      if (o[k] != a && o[k] != b && edge_sector(surface, across, k, s)) lowest_slope(s, g, lowest);
  }
  return -lowest.slope * lowest.direction;
}

// On the blended surface: the gradient's part in its tangent plane; where that plane cannot be had
// (the slopes overflow, or the surface is crushed to a line there), the facets' one-sided descent,
// so that a point is never read as stationary for want of a plane.
Vec3 blended_descent(const FrameSurface& surface, Index t, const Vec2& u, const Vec3& g, Index node,
                     const ChartPoint& where) {
  Mat32 J;
  blended_point(surface, t, u, &J);
  const Vec3 n = J.col(0).cross(J.col(1));
  const double length = n.norm();
  if (!(length > 0) || !std::isfinite(length)) return steepest_descent(surface, node, where, g);
  const Vec3 unit = n / length;
  return -(g - unit * unit.dot(g));
}

double stationarity(const FrameSurface& surface, const std::vector<Index>& movable,
                    const SlideState& state, const Positions3& gradient,
                    const ElasticMetric& metric) {
  const Index m = static_cast<Index>(movable.size());
  // The descents by coordinate, (x, y) then (z, 0): K x I3 solved as K on two 2-columns.
  Positions2 xy(m), z0(m), work;
  for (Index i = 0; i < m; ++i) {
    const Index v = movable[i];
    const Vec3 d =
        surface.blend
            ? blended_descent(surface, state.where[i].triangle, state.node_uv[v], gradient[v],
                              state.on_node[i] ? v : -1, state.where[i])
            : steepest_descent(surface, state.on_node[i] ? v : -1, state.where[i], gradient[v]);
    xy[i] = Vec2(d.x(), d.y());
    z0[i] = Vec2(d.z(), 0);
  }
  if (m == 0) return 0;
  double gain = 0;
  for (Positions2* b : {&xy, &z0}) {
    Positions2 solved = *b;
    cholesky_solve(metric.factor, solved, work);
    for (Index i = 0; i < m; ++i) gain += 0.5 * (*b)[i].dot(solved[i]);
  }
  return gain;
}

}  // namespace skinslide
