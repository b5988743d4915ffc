#include "elastic/surface_map.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include <Eigen/LU>

namespace skinslide {
namespace {

// A point whose barycentric is at most this is on the triangle's edge.
constexpr double kOnEdge = 1e-12;

// How far direction d (non-zero) points into the wedge of patch triangle t at its corner v: the
// smaller of the two normalised crosses with the wedge's edges, >= 0 inside.
double wedge_score(const Chart& chart, Index t, Index v, const Vec2& d) {
  const Triangle& tri = chart.triangles[t];
  const int c = tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
  const Vec2 a = chart.uv[tri[(c + 1) % 3]] - chart.uv[v];
  const Vec2 b = chart.uv[tri[(c + 2) % 3]] - chart.uv[v];
  return std::min(cross2(a, d) / (a.norm() * d.norm()), cross2(d, b) / (b.norm() * d.norm()));
}

}  // namespace

FrameSurface frame_surface(const Chart& chart, const Positions3& frame, const SurfaceBlend* blend) {
  FrameSurface out{chart, frame, {}, 0.0, blend, {}};
  const Index nt = chart.patch_triangle_count;
  out.normals.resize(nt);
  for (Index t = 0; t < nt; ++t) {
    const Triangle& tri = chart.triangles[t];
    out.normals[t] = (frame[tri[1]] - frame[tri[0]]).cross(frame[tri[2]] - frame[tri[0]]);
    out.area += 0.5 * out.normals[t].norm();
  }
  if (!blend) return out;
  out.facet_jacobian.resize(nt);
  for (Index t = 0; t < nt; ++t) out.facet_jacobian[t] = surface_jacobian(out, t);
  return out;
}

Mat32 surface_jacobian(const FrameSurface& surface, Index t) {
  const Triangle& tri = surface.chart.triangles[t];
  Mat32 e;
  e.col(0) = surface.frame[tri[1]] - surface.frame[tri[0]];
  e.col(1) = surface.frame[tri[2]] - surface.frame[tri[0]];
  return e * surface.chart.inverse_edges[t];
}

Vec3 surface_point(const FrameSurface& surface, const ChartPoint& p) {
  return facet_point(surface.chart, surface.frame, p);
}

Vec3 facet_point(const Chart& chart, const Positions3& frame, const ChartPoint& p) {
  const Triangle& tri = chart.triangles[p.triangle];
  return p.weight[0] * frame[tri[0]] + p.weight[1] * frame[tri[1]] + p.weight[2] * frame[tri[2]];
}

ChartPoint at_node(const Chart& chart, Index v) {
  const Index t = chart.corner_triangles[chart.corner_start[v]];
  ChartPoint p{t, {0, 0, 0}};
  for (int k = 0; k < 3; ++k) p.weight[k] = chart.triangles[t][k] == v ? 1.0 : 0.0;
  return p;
}

Mat32 node_jacobian(const FrameSurface& surface, Index v) {
  const Chart& chart = surface.chart;
  Vec3 n = Vec3::Zero();
  for (Index k = chart.corner_start[v]; k < chart.corner_start[v + 1]; ++k)
    n += surface.normals[chart.corner_triangles[k]];
  const double nn = n.norm();
  if (nn > 0) n /= nn;
  Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
  Mat32 B = Mat32::Zero();
  for (Index k = chart.corner_start[v]; k < chart.corner_start[v + 1]; ++k)
    for (Index r : chart.triangles[chart.corner_triangles[k]]) {
      if (r == v) continue;
      const Vec2 du = chart.uv[r] - chart.uv[v];
      Vec3 dx = surface.frame[r] - surface.frame[v];
      dx -= dx.dot(n) * n;
      const double w = 1.0 / std::max(du.squaredNorm(), 1e-300);
      A += w * du * du.transpose();
      B += w * dx * du.transpose();
    }
  const double det = A.determinant();
  if (!(std::abs(det) > 0) || !std::isfinite(det)) return Mat32::Zero();
  return B * A.inverse();
}

Index entered_triangle(const Chart& chart, Index node, const Vec2& u, Index t, const Vec2& d) {
  if (d.x() == 0 && d.y() == 0) return t;
  if (node >= 0) {
    Index best = t;
    double best_score = -INFINITY;
    for (Index k = chart.corner_start[node]; k < chart.corner_start[node + 1]; ++k) {
      const Index s = chart.corner_triangles[k];
      const double score = wedge_score(chart, s, node, d);
      if (score > best_score) {
        best_score = score;
        best = s;
      }
    }
    return best;
  }
  const std::array<double, 3> w = chart_barycentric(chart, t, u);
  const Vec2 dm = chart.inverse_edges[t] * d;
  const std::array<double, 3> dw{-dm.x() - dm.y(), dm.x(), dm.y()};
  Index out = t;
  double steepest = 0;
  for (int k = 0; k < 3; ++k)
    if (w[k] <= kOnEdge && dw[k] < steepest) {
      const Index nb = chart.neighbour[t][k];
      if (nb >= 0 && nb < chart.patch_triangle_count) {
        out = nb;
        steepest = dw[k];
      }
    }
  return out;
}

Vec2 redirected_from_node(const FrameSurface& surface, Index v, const Mat32& T, const Vec2& d) {
  const Chart& chart = surface.chart;
  const Vec3 motion = T * d;
  Vec2 best = d;
  double best_score = -INFINITY;
  for (Index k = chart.corner_start[v]; k < chart.corner_start[v + 1]; ++k) {
    const Index t = chart.corner_triangles[k];
    const Mat32 Tk = surface_jacobian(surface, t);
    const Eigen::Matrix2d A = Tk.transpose() * Tk;
    if (!(std::abs(A.determinant()) > 0)) continue;
    const Vec2 dk = A.inverse() * (Tk.transpose() * motion);
    if (!(dk.norm() > 0)) continue;
    const double score = wedge_score(chart, t, v, dk);
    if (score > best_score) {
      best_score = score;
      best = dk;
    }
  }
  return best;
}

}  // namespace skinslide
