#include "elastic/stationarity.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "elastic/blended_surface.h"

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

namespace {

// The curvature estimate's conjugate gradients: at most this many iterations (each one back-solve
// with the bind's factor), enough to reach nearly all of the solved estimate
// (tests/bench/elastic.md "Figures behind the code's constants").
constexpr int kCurvatureIterations = 8;
// ... and they stop once an iteration adds less than this share of the estimate.
constexpr double kCurvatureAccuracy = 1e-2;

// Per movable vertex an orthonormal basis Q of the frame's smooth tangent plane where it is (the
// frame's area-weighted vertex normals interpolated over its triangle), turned as the chart's
// axes are there (its triangle's Jacobian projected into the plane), so that neighbours' bases
// agree and the bind's factor preconditions them as it does the steps; crushed where either
// vanishes. A facet's own plane would do for a short step, but the gain left is reached by long
// ones across many facets, which a facet's plane under-reads (tests/bench/elastic.md "Honest
// stops: the first-order gain left").
std::vector<TangentFrame> smooth_tangent_frames(const FrameSurface& surface,
                                                const std::vector<Index>& movable,
                                                const SlideState& state) {
  const Chart& chart = surface.chart;
  std::vector<Vec3> normal(chart.uv.size(), Vec3::Zero());
  for (Index t = 0; t < chart.patch_triangle_count; ++t)
    for (Index v : chart.triangles[t]) normal[v] += surface.normals[t];
  std::vector<Mat32> axes(movable.size(), Mat32::Zero());
  for (size_t i = 0; i < movable.size(); ++i) {
    const ChartPoint& p = state.where[i];
    const Triangle& tri = chart.triangles[p.triangle];
    Vec3 n = Vec3::Zero();
    for (int k = 0; k < 3; ++k) n += p.weight[k] * normal[tri[k]];
    if (!(n.norm() > 0) || !n.allFinite()) continue;
    n.normalize();
    const Mat32 T = surface_jacobian(surface, p.triangle);
    axes[i] = T - n * (n.transpose() * T);
  }
  return tangent_frames(axes);
}

// A patch triangle the curvature acts on (a rest shape, a movable corner): its corners' movable
// slots (-1: stays), the gradient rows of its deformation gradient, and the energy's curvature
// there. Gathered once a measure: every conjugate-gradient iteration reads them.
struct CurvedTriangle {
  std::array<Index, 3> slot;
  std::array<Vec2, 3> G;
  TriangleCurvature curvature;
};

std::vector<CurvedTriangle> curved_triangles(const CurvatureInputs& in, const Positions3& x,
                                             const std::vector<Vec3>& frame_normals) {
  std::vector<CurvedTriangle> out;
  out.reserve(in.mesh.count);
  for (Index t = 0; t < in.mesh.count; ++t) {
    const Eigen::Matrix2d& D = in.mesh.rest_inverse[t];
    if (!has_rest_shape(D)) continue;
    const Triangle& tri = in.mesh.triangles[t];
    const std::array<Index, 3> slot{in.movable_slot[tri[0]], in.movable_slot[tri[1]],
                                    in.movable_slot[tri[2]]};
    if (slot[0] < 0 && slot[1] < 0 && slot[2] < 0) continue;
    out.push_back({slot, gradient_rows(D),
                   arap_curvature(deformation_gradient(x, tri, D), in.scale, frame_normals[t])});
  }
  return out;
}

// (Q^T H Q + shift I) a over the movable vertices; zero on those that stay. `y` and `hy` are
// work space.
void apply_curvature(const std::vector<CurvedTriangle>& curved, double weight,
                     const std::vector<TangentFrame>& frames, const std::vector<char>& stays,
                     double shift, const Positions2& a, Positions3& y, Positions3& hy,
                     Positions2& out) {
  const Index m = static_cast<Index>(a.size());
  for (Index i = 0; i < m; ++i) y[i] = stays[i] ? Vec3::Zero() : Vec3(frames[i].Q * a[i]);
  hy.assign(m, Vec3::Zero());
  for (const CurvedTriangle& c : curved) {
    Mat32 dJ = Mat32::Zero();
    for (int k = 0; k < 3; ++k)
      if (c.slot[k] >= 0) dJ += y[c.slot[k]] * c.G[k].transpose();
    if (dJ.isZero(0)) continue;
    const Mat32 dE = weight * c.curvature.times(dJ);
    for (int k = 0; k < 3; ++k)
      if (c.slot[k] >= 0) hy[c.slot[k]] += dE * c.G[k];
  }
  for (Index i = 0; i < m; ++i)
    out[i] = stays[i] ? Vec2::Zero() : Vec2(frames[i].Q.transpose() * hy[i] + shift * a[i]);
}

// 1/2 b^T (Q^T H Q)^-1 b, b = Q^T rho, by conjugate gradients from zero preconditioned by K's
// factor on both tangent coordinates: each iteration adds 1/2 alpha r.z to the estimate, which
// only grows (a truncated solve reads low, never high).
double curvature_gain(const SlideState& state, const FrameSurface& surface,
                      const std::vector<Index>& movable, const ElasticMetric& metric,
                      const CurvatureInputs& in, const Positions3& rho) {
  const Index m = static_cast<Index>(rho.size());
  const std::vector<TangentFrame> frames = smooth_tangent_frames(surface, movable, state);
  const std::vector<CurvedTriangle> curved = curved_triangles(in, state.x, surface.normals);
  std::vector<char> stays(m);
  Positions2 r(m), z, p(m, Vec2::Zero()), Ap(m), work;
  Positions3 y(m), hy;
  for (Index i = 0; i < m; ++i) {
    stays[i] = frames[i].crushed;
    r[i] = stays[i] ? Vec2::Zero() : Vec2(frames[i].Q.transpose() * rho[i]);
  }
  double gain = 0, rz_last = 0;
  for (int it = 0; it < kCurvatureIterations; ++it) {
    z = r;
    cholesky_solve(metric.factor, z, work);
    for (Index i = 0; i < m; ++i)
      if (stays[i]) z[i].setZero();
    const double rz = dot(r, z);
    if (!(rz > 0)) break;
    const double beta = it == 0 ? 0.0 : rz / rz_last;
    for (Index i = 0; i < m; ++i) p[i] = z[i] + beta * p[i];
    rz_last = rz;
    apply_curvature(curved, in.mesh.weight, frames, stays, metric.shift, p, y, hy, Ap);
    const double pAp = dot(p, Ap);
    if (!(pAp > 0)) break;
    const double alpha = rz / pAp;
    for (Index i = 0; i < m; ++i) r[i] -= alpha * Ap[i];
    const double added = 0.5 * alpha * rz;
    gain += added;
    if (added <= kCurvatureAccuracy * gain) break;
  }
  return gain;
}

}  // namespace

FirstOrderGain stationarity(const FrameSurface& surface, const std::vector<Index>& movable,
                            const SlideState& state, const Positions3& gradient,
                            const ElasticMetric& metric, const CurvatureInputs& curvature,
                            double short_of) {
  const Index m = static_cast<Index>(movable.size());
  Positions3 rho(m);
  // The descents by coordinate, (x, y) then (z, 0): K x I3 solved as K on two 2-columns.
  Positions2 xy(m), z0(m), work;
  for (Index i = 0; i < m; ++i) {
    const Index v = movable[i];
    rho[i] = surface.blend ? blended_descent(surface, state.where[i].triangle, state.node_uv[v],
                                             gradient[v], state.on_node[i] ? v : -1, state.where[i])
                           : steepest_descent(surface, state.on_node[i] ? v : -1, state.where[i],
                                              gradient[v]);
    xy[i] = Vec2(rho[i].x(), rho[i].y());
    z0[i] = Vec2(rho[i].z(), 0);
  }
  FirstOrderGain gain;
  if (m == 0) return gain;
  for (Positions2* b : {&xy, &z0}) {
    Positions2 solved = *b;
    cholesky_solve(metric.factor, solved, work);
    for (Index i = 0; i < m; ++i) gain.bind_metric += 0.5 * (*b)[i].dot(solved[i]);
  }
  if (gain.bind_metric > short_of) return gain;
  gain.curvature = curvature_gain(state, surface, movable, metric, curvature, rho);
  return gain;
}

}  // namespace skinslide
