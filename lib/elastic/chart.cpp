#include "elastic/chart.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SparseLU>

#include "core/check.h"
#include "core/error.h"
#include "locate/barycentric.h"
#include "locate/locate.h"

namespace skinslide {
namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// tan(angle/2) between e1 and e2, from sin/(1 + cos): stable down to zero angles.
double half_angle_tangent(const Vec3& e1, const Vec3& e2) {
  const double s = e1.cross(e2).norm();
  const double c = e1.norm() * e2.norm() + e1.dot(e2);
  if (!(c > 0)) return s > 0 ? 1e12 : 0.0;  // a straight angle: as steep as we allow
  return std::min(s / c, 1e12);
}

// Node positions of the filled disk for the given weights (uniform or mean value); the outer
// loop's nodes are fixed at `outer_uv`.
Positions2 embed(const Positions3& x3, const std::vector<Triangle>& triangles,
                 const std::vector<Index>& outer, const Positions2& outer_uv, bool mean_value) {
  const Index n = static_cast<Index>(x3.size());
  // Row i of the weights, as (j, w) pairs; summed into a sparse matrix.
  std::vector<Triplet> w;
  std::vector<Triplet> uniform;
  w.reserve(triangles.size() * 6);
  uniform.reserve(triangles.size() * 6);
  for (const Triangle& t : triangles)
    for (int k = 0; k < 3; ++k) {
      const Index i = t[k], j = t[(k + 1) % 3], l = t[(k + 2) % 3];
      // Each undirected edge appears in one or two triangles: the 0.5 makes inner edges 1.
      uniform.emplace_back(i, j, 0.5);
      uniform.emplace_back(i, l, 0.5);
      if (!mean_value) continue;
      const Vec3 eij = x3[j] - x3[i], eil = x3[l] - x3[i];
      const double tn = half_angle_tangent(eij, eil);
      const double lij = eij.norm(), lil = eil.norm();
      if (lij > 0) w.emplace_back(i, j, tn / lij);
      if (lil > 0) w.emplace_back(i, l, tn / lil);
    }
  SparseMatrix U(n, n), W(n, n);
  U.setFromTriplets(uniform.begin(), uniform.end());
  for (int k = 0; k < U.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(U, k); it; ++it) it.valueRef() = 1.0;
  const Eigen::VectorXd u_rows = U * Eigen::VectorXd::Ones(n);
  SparseMatrix A(n, n);
  if (mean_value) {
    W.setFromTriplets(w.begin(), w.end());
    Eigen::VectorXd rows = W * Eigen::VectorXd::Ones(n);
    // Row-normalised mean-value weights, plus a 1e-9 share of uniform ones so that every edge
    // weighs strictly more than zero (a zero-length edge or a flat corner gives a zero weight).
    std::vector<Triplet> all;
    for (int k = 0; k < W.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(W, k); it; ++it)
        if (rows[it.row()] > 0 && std::isfinite(rows[it.row()]) && std::isfinite(it.value()))
          all.emplace_back(it.row(), it.col(), it.value() / rows[it.row()]);
    for (int k = 0; k < U.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(U, k); it; ++it)
        all.emplace_back(it.row(), it.col(), 1e-9 / u_rows[it.row()]);
    A.setFromTriplets(all.begin(), all.end());
  } else {
    A = U;
  }
  std::vector<char> fixed(n, 0);
  for (Index v : outer) fixed[v] = 1;
  std::vector<Index> slot(n, -1);
  Index m = 0;
  for (Index v = 0; v < n; ++v)
    if (!fixed[v]) slot[v] = m++;
  Positions2 uv(n, Vec2::Zero());
  for (size_t k = 0; k < outer.size(); ++k) uv[outer[k]] = outer_uv[k];
  if (m == 0) return uv;
  // Row i: (sum_j a_ij) u_i - sum_j a_ij u_j = 0 for every node not on the outer loop.
  std::vector<Triplet> lt;
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(m, 2);
  for (int k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A, k); it; ++it) {
      const Index i = static_cast<Index>(it.row()), j = static_cast<Index>(it.col());
      if (fixed[i] || i == j) continue;
      lt.emplace_back(slot[i], slot[i], it.value());
      if (fixed[j])
        rhs.row(slot[i]) += it.value() * uv[j].transpose();
      else
        lt.emplace_back(slot[i], slot[j], -it.value());
    }
  SparseMatrix L(m, m);
  L.setFromTriplets(lt.begin(), lt.end());
  L.makeCompressed();
  Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(L);
  if (lu.info() != Eigen::Success)
    throw Error(ErrorKind::Numeric, "the chart's embedding cannot be solved");
  const Eigen::MatrixX2d x = lu.solve(rhs);
  for (Index v = 0; v < n; ++v)
    if (!fixed[v]) uv[v] = x.row(slot[v]).transpose();
  return uv;
}

}  // namespace

Chart disk_chart(const Positions3& points, const std::vector<Triangle>& triangles,
                 const std::vector<std::vector<Index>>& loops, Index outer_loop) {
  SKINSLIDE_CHECK(outer_loop >= 0 && outer_loop < static_cast<Index>(loops.size()), "outer loop");
  const Index n = static_cast<Index>(points.size());
  Chart chart;
  chart.patch_triangle_count = static_cast<Index>(triangles.size());
  chart.triangles = triangles;
  Positions3 x3 = points;
  for (size_t l = 0; l < loops.size(); ++l) {
    if (static_cast<Index>(l) == outer_loop) continue;
    const auto& loop = loops[l];
    Vec3 centre = Vec3::Zero();
    for (Index v : loop) centre += points[v];
    const Index c = static_cast<Index>(x3.size());
    x3.push_back(centre / static_cast<double>(loop.size()));
    for (size_t k = 0; k < loop.size(); ++k)
      chart.triangles.push_back({c, loop[k], loop[(k + 1) % loop.size()]});
  }
  const auto& outer = loops[outer_loop];
  std::vector<double> arc(outer.size() + 1, 0.0);
  for (size_t k = 0; k < outer.size(); ++k)
    arc[k + 1] = arc[k] + (points[outer[(k + 1) % outer.size()]] - points[outer[k]]).norm();
  if (!(arc.back() > 0) || !std::isfinite(arc.back()))
    throw Error(ErrorKind::Input, "the outer boundary loop (from vertex " +
                                      std::to_string(outer.front()) + ") has zero length");
  Positions2 outer_uv(outer.size());
  const double n_outer = static_cast<double>(outer.size());
  for (size_t k = 0; k < outer.size(); ++k) {
    // By arc length, with a thousandth of even spacing so that a zero-length border edge still
    // gets two distinct points.
    const double a = 2 * std::numbers::pi *
                     (0.999 * arc[k] / arc.back() + 0.001 * static_cast<double>(k) / n_outer);
    outer_uv[k] = Vec2(0.5 + 0.5 * std::cos(a), 0.5 + 0.5 * std::sin(a));
  }
  const auto area = [&](const Positions2& uv, const Triangle& t) {
    return cross2(uv[t[1]] - uv[t[0]], uv[t[2]] - uv[t[0]]);
  };
  for (const bool mean_value : {true, false}) {
    Positions2 uv = embed(x3, chart.triangles, outer, outer_uv, mean_value);
    Index positive = 0, negative = 0;
    for (Index t = 0; t < chart.patch_triangle_count; ++t) {
      const double a = area(uv, chart.triangles[t]);
      positive += a > 0;
      negative += a < 0;
    }
    if (negative > positive)
      for (Vec2& p : uv) p.y() = 1.0 - p.y();  // mirror: the patch's triangles counter-clockwise
    bool flat = false;
    for (size_t t = 0; t < chart.triangles.size(); ++t) {
      Triangle& tri = chart.triangles[t];
      if (static_cast<Index>(t) >= chart.patch_triangle_count && area(uv, tri) < 0)
        std::swap(tri[1], tri[2]);  // fill triangles follow the chart, not the hole's winding
      flat = flat || !(area(uv, tri) > 0);
    }
    if (!flat) {
      chart.uv = std::move(uv);
      chart.uniform_weights = !mean_value;
      break;
    }
  }
  if (chart.uv.empty())
    throw Error(ErrorKind::Numeric,
                "the patch's chart has a triangle without area even with uniform weights "
                "(triangles far smaller than the patch's; split the patch)");
  const Index nodes = static_cast<Index>(chart.uv.size());
  TriangleTopology topo = triangle_topology(chart.triangles, nodes);
  chart.neighbour = std::move(topo.neighbour);
  chart.inverse_edges.resize(chart.triangles.size());
  for (size_t t = 0; t < chart.triangles.size(); ++t) {
    const Triangle& tri = chart.triangles[t];
    Eigen::Matrix2d m;
    m.col(0) = chart.uv[tri[1]] - chart.uv[tri[0]];
    m.col(1) = chart.uv[tri[2]] - chart.uv[tri[0]];
    chart.inverse_edges[t] = m.inverse();
  }
  // Patch triangles around each patch vertex (the fill triangles come after them).
  chart.corner_start.assign(static_cast<size_t>(n) + 1, 0);
  for (Index t = 0; t < chart.patch_triangle_count; ++t)
    for (Index v : chart.triangles[t]) ++chart.corner_start[v + 1];
  for (Index v = 0; v < n; ++v) chart.corner_start[v + 1] += chart.corner_start[v];
  chart.corner_triangles.resize(chart.corner_start.back());
  std::vector<Index> fill(chart.corner_start.begin(), chart.corner_start.end() - 1);
  for (Index t = 0; t < chart.patch_triangle_count; ++t)
    for (Index v : chart.triangles[t]) chart.corner_triangles[fill[v]++] = t;
  return chart;
}

std::array<double, 3> chart_barycentric(const Chart& chart, Index t, const Vec2& p) {
  const Vec2 bc = chart.inverse_edges[t] * (p - chart.uv[chart.triangles[t][0]]);
  return {1.0 - bc.x() - bc.y(), bc.x(), bc.y()};
}

namespace {

ChartPoint clamped(Index t, std::array<double, 3> w) {
  double sum = 0;
  for (double& x : w) {
    x = std::max(x, 0.0);
    sum += x;
  }
  if (!(sum > 0)) return {t, {1, 0, 0}};
  for (double& x : w) x /= sum;
  return {t, w};
}

}  // namespace

ChartPoint locate_in_chart(const Chart& chart, const Vec2& p, Index start) {
  const Index count = static_cast<Index>(chart.triangles.size());
  Index t = start;
  std::array<double, 3> w{};
  bool done = false;
  for (Index step = 0; step <= count; ++step) {
    w = chart_barycentric(chart, t, p);
    const int k = w[0] <= w[1] ? (w[0] <= w[2] ? 0 : 2) : (w[1] <= w[2] ? 1 : 2);
    if (w[k] >= -kInsideEps || chart.neighbour[t][k] < 0) {
      done = true;
      break;
    }
    t = chart.neighbour[t][k];
  }
  if (!done) {
    // An injective chart has no cycles to walk in; round-off near a vertex still might.
    double best = INFINITY;
    for (Index s = 0; s < chart.patch_triangle_count; ++s) {
      const Triangle& tri = chart.triangles[s];
      const ClosestPoint c = closest_point(p, chart.uv[tri[0]], chart.uv[tri[1]], chart.uv[tri[2]]);
      if (c.distance2 < best) {
        best = c.distance2;
        t = s;
        w = c.w;
      }
    }
    return clamped(t, w);
  }
  if (t >= chart.patch_triangle_count) {
    // In a hole by round-off: corner 0 of a fill triangle is its centre, so the loop edge is
    // opposite it.
    t = chart.neighbour[t][0];
    SKINSLIDE_CHECK(t >= 0 && t < chart.patch_triangle_count, "a hole's edge borders the patch");
    w = chart_barycentric(chart, t, p);
  }
  return clamped(t, w);
}

}  // namespace skinslide
