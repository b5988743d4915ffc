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
#include "solve/smoothed_aggregation.h"

namespace skinslide {
namespace {

// tan(angle/2) between e1 and e2 (of lengths l1, l2), from sin/(1 + cos): stable down to zero
// angles.
double half_angle_tangent(const Vec3& e1, const Vec3& e2, double l1, double l2) {
  const double s = e1.cross(e2).norm();
  const double c = l1 * l2 + e1.dot(e2);
  if (!(c > 0)) return s > 0 ? 1e12 : 0.0;  // a straight angle: as steep as we allow
  return std::min(s / c, 1e12);
}

// The embedding's linear system: row r is node `node[r]` (every node off the outer loop, in node
// order), (sum_j a_ij) u_i - sum_j a_ij u_j = 0 with the outer loop's nodes moved to the right-hand
// side; both coordinates at once. Every sum has a fixed order (an edge's weight over its
// triangles in triangle order, a row's sums in ascending neighbour order): the order of the
// triplet assembly this replaced, so that the direct solve gives, bit for bit, the charts it gave.
struct EmbeddingSystem {
  std::vector<Index> slot;  // node -> row; -1 on the outer loop
  std::vector<Index> node;  // row -> node
  RowMatrix L;
  Eigen::MatrixX2d rhs;
};

// One corner's view of one of its edges: the other end and its mean-value weight (none for an
// edge of zero length).
struct Incidence {
  Index j;
  bool weighted;
  double w;
};

EmbeddingSystem embedding_system(const Positions3& x3, const std::vector<Triangle>& triangles,
                                 const std::vector<Index>& outer, const Positions2& outer_uv,
                                 bool mean_value) {
  const Index n = static_cast<Index>(x3.size());
  EmbeddingSystem sys;
  sys.slot.assign(n, -1);
  std::vector<char> fixed(n, 0);
  for (Index v : outer) fixed[v] = 1;
  for (Index v = 0; v < n; ++v)
    if (!fixed[v]) {
      sys.slot[v] = static_cast<Index>(sys.node.size());
      sys.node.push_back(v);
    }
  const Index m = static_cast<Index>(sys.node.size());
  // The corners of each row's node (3 t + k: corner k of triangle t), in triangle order.
  std::vector<Index> first(static_cast<size_t>(m) + 1, 0);
  for (const Triangle& t : triangles)
    for (Index v : t)
      if (sys.slot[v] >= 0) ++first[sys.slot[v] + 1];
  for (Index r = 0; r < m; ++r) first[r + 1] += first[r];
  std::vector<Index> around(first.back());
  {
    std::vector<Index> next(first.begin(), first.end() - 1);
    for (Index t = 0; t < static_cast<Index>(triangles.size()); ++t)
      for (int k = 0; k < 3; ++k)
        if (sys.slot[triangles[t][k]] >= 0) around[next[sys.slot[triangles[t][k]]]++] = 3 * t + k;
  }
  Positions2 uv_fixed(n, Vec2::Zero());
  for (size_t k = 0; k < outer.size(); ++k) uv_fixed[outer[k]] = outer_uv[k];
  RowMatrix& L = sys.L;
  L.rows = m;
  L.start.assign(1, 0);
  L.column.reserve(2 * around.size() + static_cast<size_t>(m));
  L.value.reserve(2 * around.size() + static_cast<size_t>(m));
  sys.rhs = Eigen::MatrixX2d::Zero(m, 2);
  // A row's distinct neighbours, ascending, an edge's weights from its two triangles summed (a sum
  // of two terms: their order cannot matter).
  std::vector<Incidence> edges(16);
  std::vector<Index> seen(n, -1);      // node -> its entry in `edges`...
  std::vector<Index> seen_row(n, -1);  // ... for this row
  for (Index r = 0; r < m; ++r) {
    const Index i = sys.node[r];
    size_t kept = 0;
    const auto add = [&](Index j, double length, double tn) {
      const Incidence e{j, length > 0, length > 0 ? tn / length : 0.0};
      if (seen_row[j] == r) {
        Incidence& f = edges[seen[j]];
        if (e.weighted) f.w = f.weighted ? f.w + e.w : e.w;
        f.weighted = f.weighted || e.weighted;
        return;
      }
      if (kept == edges.size()) edges.resize(2 * kept);
      seen_row[j] = r;
      seen[j] = static_cast<Index>(kept);
      edges[kept++] = e;
    };
    for (Index q = first[r]; q < first[r + 1]; ++q) {
      // w_ij += tan(angle_i / 2) / |x_j - x_i| over the triangles with corner i and edge ij.
      const Triangle& t = triangles[around[q] / 3];
      const int k = around[q] % 3;
      const Index j = t[(k + 1) % 3], l = t[(k + 2) % 3];
      if (!mean_value) {
        add(j, 0, 0);
        add(l, 0, 0);
        continue;
      }
      const Vec3 eij = x3[j] - x3[i], eil = x3[l] - x3[i];
      const double lij = eij.norm(), lil = eil.norm();
      const double tn = half_angle_tangent(eij, eil, lij, lil);
      add(j, lij, tn);
      add(l, lil, tn);
    }
    const auto by_node = [](const Incidence& a, const Incidence& b) { return a.j < b.j; };
    if (kept > 32)  // a hole's centre: as many neighbours as its loop has vertices
      std::sort(edges.begin(), edges.begin() + static_cast<std::ptrdiff_t>(kept), by_node);
    else  // insertion sort: a handful of neighbours
      for (size_t q = 1; q < kept; ++q)
        for (size_t p = q; p > 0 && by_node(edges[p], edges[p - 1]); --p)
          std::swap(edges[p], edges[p - 1]);
    // a_ij: the row-normalised mean-value weight plus 1e-9 / deg(i), so that every edge weighs
    // strictly more than zero (a zero-length edge or a flat corner gives a zero weight); or 1.
    const double uniform = 1e-9 / static_cast<double>(kept);
    double row = 0;
    if (mean_value)
      for (size_t q = 0; q < kept; ++q)
        if (edges[q].weighted) row += edges[q].w;
    const bool normalise = mean_value && row > 0 && std::isfinite(row);
    double diagonal = 0;
    bool first_term = true;
    Index diagonal_at = -1;
    for (size_t q = 0; q < kept; ++q) {
      const Incidence& e = edges[q];
      const Index j = e.j;
      if (j == i) continue;
      const double aij = !mean_value                                     ? 1.0
                         : normalise && e.weighted && std::isfinite(e.w) ? e.w / row + uniform
                                                                         : uniform;
      diagonal = first_term ? aij : diagonal + aij;
      first_term = false;
      if (fixed[j]) {
        sys.rhs.row(r) += aij * uv_fixed[j].transpose();
        continue;
      }
      if (diagonal_at < 0 && j > i) {
        diagonal_at = static_cast<Index>(L.column.size());
        L.column.push_back(r);
        L.value.push_back(0.0);
      }
      L.column.push_back(sys.slot[j]);
      L.value.push_back(-aij);
    }
    if (diagonal_at < 0) {
      diagonal_at = static_cast<Index>(L.column.size());
      L.column.push_back(r);
      L.value.push_back(0.0);
    }
    L.value[diagonal_at] = diagonal;
    L.start.push_back(static_cast<Index>(L.column.size()));
  }
  return sys;
}

// The nodes' chart positions from the system's solution (the outer loop's as given).
Positions2 scatter(const EmbeddingSystem& sys, const Eigen::MatrixX2d& x,
                   const std::vector<Index>& outer, const Positions2& outer_uv) {
  Positions2 uv(sys.slot.size(), Vec2::Zero());
  for (size_t k = 0; k < outer.size(); ++k) uv[outer[k]] = outer_uv[k];
  for (size_t r = 0; r < sys.node.size(); ++r) uv[sys.node[r]] = x.row(r).transpose();
  return uv;
}

// One sparse LU solve (COLAMD order).
Eigen::MatrixX2d solve_directly(const EmbeddingSystem& sys) {
  const RowMatrix& L = sys.L;
  const Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor, Index>> rows(
      L.rows, L.rows, static_cast<Index>(L.column.size()), L.start.data(), L.column.data(),
      L.value.data());
  SparseMatrix A = rows;
  A.makeCompressed();
  Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(A);
  if (lu.info() != Eigen::Success)
    throw Error(ErrorKind::Numeric, "the chart's embedding cannot be solved");
  return lu.solve(sys.rhs);
}

}  // namespace

Chart disk_chart(const Positions3& points, const std::vector<Triangle>& triangles,
                 const std::vector<std::vector<Index>>& loops, Index outer_loop,
                 const ChartSolver& solver) {
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
  // Mirrors uv if most patch triangles come out clockwise and winds the fill triangles
  // counter-clockwise (into `wound`); false if a triangle then has no area.
  const auto oriented = [&](Positions2& uv, std::vector<Triangle>& wound) {
    Index positive = 0, negative = 0;
    for (Index t = 0; t < chart.patch_triangle_count; ++t) {
      const double a = area(uv, chart.triangles[t]);
      positive += a > 0;
      negative += a < 0;
    }
    if (negative > positive)
      for (Vec2& p : uv) p.y() = 1.0 - p.y();  // mirror: the patch's triangles counter-clockwise
    wound = chart.triangles;
    bool flat = false;
    for (size_t t = 0; t < wound.size(); ++t) {
      Triangle& tri = wound[t];
      if (static_cast<Index>(t) >= chart.patch_triangle_count && area(uv, tri) < 0)
        std::swap(tri[1], tri[2]);  // fill triangles follow the chart, not the hole's winding
      flat = flat || !(area(uv, tri) > 0);
    }
    return !flat;
  };
  // Mean-value weights, else uniform ones; each solved iteratively when the system is large (an
  // approximate solution is kept only when every triangle has area), else, or then, directly.
  for (const bool mean_value : {true, false}) {
    const EmbeddingSystem sys = embedding_system(x3, chart.triangles, outer, outer_uv, mean_value);
    const Index rows = sys.L.rows;
    bool done = false;
    for (const bool iterative : {true, false}) {
      if (iterative && (rows == 0 || rows < solver.iterative_from)) continue;
      Eigen::MatrixX2d x = Eigen::MatrixX2d::Zero(rows, 2);
      if (iterative) {
        if (!solve_smoothed_aggregation(sys.L, sys.rhs, x, solver.tolerance, solver.max_iterations)
                 .converged)
          continue;
      } else if (rows > 0) {
        x = solve_directly(sys);
      }
      Positions2 uv = scatter(sys, x, outer, outer_uv);
      std::vector<Triangle> wound;
      if (!oriented(uv, wound)) continue;
      chart.uv = std::move(uv);
      chart.triangles = std::move(wound);
      chart.uniform_weights = !mean_value;
      chart.iterative = iterative;
      done = true;
      break;
    }
    if (done) break;
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
