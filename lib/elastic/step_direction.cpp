#include "elastic/step_direction.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>

namespace skinslide {
namespace {

// held_direction: the rings around a held vertex that are relaxed, and the sweeps over them.
constexpr int kHeldRings = 4;
constexpr int kHeldSweeps = 8;
// The metric's shift, as a share of its mean diagonal.
constexpr double kShift = 1e-12;
// A Jacobian this close to rank one (det(T^T T) <= 1e-8 trace^2: singular values' ratio 1e-4)
// is crushed.
constexpr double kWellConditioned = 1e-8;

TangentFrame one_tangent_frame(const Mat32& T) {
  TangentFrame out;
  const Eigen::Matrix2d M = T.transpose() * T;
  const double trace = M.trace(), det = M.determinant();
  if (!(trace > 0) || !std::isfinite(trace) || !(det > kWellConditioned * trace * trace))
    return out;
  const Eigen::Matrix2d S = M.llt().matrixU();
  out.S_inverse = S.inverse();
  out.Q = T * out.S_inverse;
  out.crushed = false;
  return out;
}

// (Q^T (K x I3) Q + shift I) p over the vertices that do not stay (p is zero on the others,
// and so is the product).
void apply_system(const ElasticMetric& metric, const std::vector<TangentFrame>& frame,
                  const std::vector<char>& stays, const Positions2& p, Positions3& motion,
                  Positions2& out) {
  const Index m = metric.size();
  for (Index j = 0; j < m; ++j) motion[j] = stays[j] ? Vec3::Zero() : Vec3(frame[j].Q * p[j]);
  for (Index i = 0; i < m; ++i) {
    if (stays[i]) {
      out[i].setZero();
      continue;
    }
    Vec3 sum = Vec3::Zero();
    for (Index e = metric.start[i]; e < metric.start[i + 1]; ++e)
      sum += metric.value[e] * motion[metric.column[e]];
    out[i] = frame[i].Q.transpose() * sum + metric.shift * p[i];
  }
}

}  // namespace

double dot(const Positions2& a, const Positions2& b) {
  double total = 0;
  for (size_t i = 0; i < a.size(); ++i) total += a[i].dot(b[i]);
  return total;
}

ElasticMetric elastic_metric(const ArapTriangles& mesh, const std::vector<Index>& movable_slot,
                             Index count) {
  // Per movable vertex the triangles around it (with a rest shape), ascending.
  std::vector<Index> around_start(count + 1, 0), around;
  for (Index t = 0; t < mesh.count; ++t)
    if (has_rest_shape(mesh.rest_inverse[t]))
      for (Index v : mesh.triangles[t])
        if (const Index i = movable_slot[v]; i >= 0) ++around_start[i + 1];
  for (Index i = 0; i < count; ++i) around_start[i + 1] += around_start[i];
  around.resize(around_start[count]);
  std::vector<Index> fill(around_start.begin(), around_start.end() - 1);
  for (Index t = 0; t < mesh.count; ++t)
    if (has_rest_shape(mesh.rest_inverse[t]))
      for (Index v : mesh.triangles[t])
        if (const Index i = movable_slot[v]; i >= 0) around[fill[i]++] = t;
  // Row i: sum over its triangles of 2 w G_k . G_l, entries merged by column in triangle order
  // (every movable vertex keeps a diagonal entry, even with no rest shape around it).
  ElasticMetric out;
  out.start.assign(1, 0);
  std::vector<std::pair<Index, double>> row;
  for (Index i = 0; i < count; ++i) {
    row.assign(1, {i, 0.0});
    for (Index a = around_start[i]; a < around_start[i + 1]; ++a) {
      const Index t = around[a];
      const Triangle& tri = mesh.triangles[t];
      const std::array<Vec2, 3> G = gradient_rows(mesh.rest_inverse[t]);
      const int k = movable_slot[tri[0]] == i ? 0 : movable_slot[tri[1]] == i ? 1 : 2;
      for (int l = 0; l < 3; ++l)
        if (const Index j = movable_slot[tri[l]]; j >= 0)
          row.emplace_back(j, 2 * mesh.weight * G[k].dot(G[l]));
    }
    std::stable_sort(row.begin(), row.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    for (size_t e = 0; e < row.size(); ++e) {
      if (e > 0 && row[e].first == row[e - 1].first) {
        out.value.back() += row[e].second;
        continue;
      }
      out.column.push_back(row[e].first);
      out.value.push_back(row[e].second);
    }
    out.start.push_back(static_cast<Index>(out.column.size()));
  }
  if (count == 0) return out;
  double trace = 0;
  std::vector<double> shifted = out.value;
  for (Index i = 0; i < count; ++i)
    for (Index e = out.start[i]; e < out.start[i + 1]; ++e)
      if (out.column[e] == i) trace += out.value[e];
  out.shift = kShift * trace / count + 1e-300;
  for (Index i = 0; i < count; ++i)
    for (Index e = out.start[i]; e < out.start[i + 1]; ++e)
      if (out.column[e] == i) shifted[e] += out.shift;
  // K is symmetric: its compressed rows are its compressed columns.
  out.factor =
      cholesky_factor(SymmetricView{count, out.start.data(), out.column.data(), shifted.data()});
  return out;
}

std::vector<TangentFrame> tangent_frames(const std::vector<Mat32>& T) {
  std::vector<TangentFrame> out(T.size());
  for (size_t i = 0; i < T.size(); ++i) out[i] = one_tangent_frame(T[i]);
  return out;
}

StepDirection step_direction(const ElasticMetric& metric, const std::vector<TangentFrame>& frames,
                             const Positions3& gradient, const std::vector<char>& held,
                             DirectionWork& work, const DirectionSolve& solve) {
  const Index m = metric.size();
  StepDirection out;
  out.d.assign(m, Vec2::Zero());
  std::vector<char>& stays = work.stays;
  stays.resize(m);
  for (Index i = 0; i < m; ++i) stays[i] = (!held.empty() && held[i]) || frames[i].crushed;
  const auto is_held = [&](Index i) { return stays[i] != 0; };
  Positions2 &r = work.r, &x = work.x;
  r.resize(m);
  x.assign(m, Vec2::Zero());  // held_direction reads it, also after a zero gradient
  work.motion.resize(m);
  for (Index i = 0; i < m; ++i) {
    r[i] = is_held(i) ? Vec2::Zero() : Vec2(-(frames[i].Q.transpose() * gradient[i]));
  }
  const double r0 = std::sqrt(dot(r, r));
  if (!(r0 > 0)) {
    out.finite = std::isfinite(r0);
    return out;
  }
  const double r_stop = solve.tolerance * solve.tolerance * r0 * r0;
  out.iterations = conjugate_gradients(
      work, solve.max_iterations,
      [&](Positions2& z) {
        // The bind's factor sees every vertex free: held ones are masked out around it.
        cholesky_solve(metric.factor, z, work.permuted);
        for (Index i = 0; i < m; ++i)
          if (is_held(i)) z[i].setZero();
      },
      [&](const Positions2& p, Positions2& Ap) {
        apply_system(metric, frames, stays, p, work.motion, Ap);
      },
      [&](const Positions2& residual) { return dot(residual, residual) > r_stop; });
  out.capped = out.iterations >= solve.max_iterations && dot(r, r) > r_stop;
  out.residual = std::sqrt(dot(r, r)) / r0;
  for (Index i = 0; i < m; ++i) {
    out.d[i] = is_held(i) ? Vec2::Zero() : Vec2(frames[i].S_inverse * x[i]);
    if (!out.d[i].allFinite()) out.finite = false;
  }
  if (!out.finite) out.d.assign(m, Vec2::Zero());
  return out;
}

StepDirection held_direction(const ElasticMetric& metric, const std::vector<TangentFrame>& frames,
                             const Positions3& gradient, const std::vector<char>& held,
                             DirectionWork& work) {
  const Index m = metric.size();
  StepDirection out;
  out.d.assign(m, Vec2::Zero());
  Positions2& x = work.x;
  // The vertices within kHeldRings of a held one, free, ascending: the ones relaxed.
  std::vector<int> ring(m, -1);
  std::vector<Index> frontier;
  const auto is_held = [&](Index i) { return held[i] || frames[i].crushed; };
  for (Index i = 0; i < m; ++i)
    if (is_held(i)) {
      ring[i] = 0;
      frontier.push_back(i);
      x[i].setZero();
    }
  for (int r = 1; r <= kHeldRings; ++r) {
    std::vector<Index> next;
    for (Index i : frontier)
      for (Index e = metric.start[i]; e < metric.start[i + 1]; ++e)
        if (const Index j = metric.column[e]; ring[j] < 0) {
          ring[j] = r;
          next.push_back(j);
        }
    frontier = std::move(next);
  }
  std::vector<Index> region;
  for (Index i = 0; i < m; ++i)
    if (ring[i] > 0) region.push_back(i);
  // Gauss-Seidel on (Q^T (K x I3) Q + shift I) x = -Q^T g over the region, forward then
  // backward: coordinate descent on the step's model, so the model only falls.
  const auto relax_vertex = [&](Index i) {
    const TangentFrame& fi = frames[i];
    Vec3 sum = Vec3::Zero();
    double diagonal = 0;
    for (Index e = metric.start[i]; e < metric.start[i + 1]; ++e) {
      const Index j = metric.column[e];
      if (j == i)
        diagonal = metric.value[e];
      else if (!is_held(j))
        sum += metric.value[e] * (frames[j].Q * x[j]);
    }
    const Vec2 rhs = -(fi.Q.transpose() * (gradient[i] + sum));
    const Eigen::Matrix2d A =
        diagonal * (fi.Q.transpose() * fi.Q) + metric.shift * Eigen::Matrix2d::Identity();
    x[i] = A.inverse() * rhs;
  };
  for (int sweep = 0; sweep < kHeldSweeps; ++sweep) {
    for (Index i : region) relax_vertex(i);
    for (auto it = region.rbegin(); it != region.rend(); ++it) relax_vertex(*it);
  }
  for (Index i = 0; i < m; ++i) {
    out.d[i] = is_held(i) ? Vec2::Zero() : Vec2(frames[i].S_inverse * x[i]);
    if (!out.d[i].allFinite()) out.finite = false;
  }
  if (!out.finite) out.d.assign(m, Vec2::Zero());
  return out;
}

}  // namespace skinslide
