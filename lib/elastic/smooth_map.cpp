#include "elastic/smooth_map.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "core/error.h"
#include "elastic/arap.h"
#include "elastic/step_direction.h"

namespace skinslide {
namespace {

// A slid triangle whose singular values' ratio s2 / s1 falls below this share counts less in the
// pass's energy, by smoothstep(ratio / kCrushed), and not at all when crushed to a line: its
// rotation is then undefined, and a fit that jumped would move the slide with it.
constexpr double kCrushed = 0.05;
// Levenberg-Marquardt damping of each pass's step where the frame's surface is crushed: this share
// of the vertex's own stiffness K_ii in the directions its tangent frame loses, K_ii (I - Q^T Q)
// (0 where T is well conditioned, K_ii along a direction crushed to nothing). It bounds the step
// where a chart step hardly moves the point; elsewhere the step is Gauss-Newton's (a damping of
// every direction held the smooth modes of a large patch in place: tests/bench/elastic.md
// "Figures behind the code's constants").
constexpr double kDamping = 1.0;
// A tangent frame's Jacobian T is regularised by this share of trace(T^T T) before its Cholesky
// factor is taken: S^T S = T^T T + kTangentFloor trace I is continuous and definite for any
// non-zero T (the search holds such vertices instead: a branch).
constexpr double kTangentFloor = 1e-4;
// A pass changes a triangle's edges by less than this share of its smallest altitude (below one
// half it cannot fold), saturating smoothly (step_shares).
constexpr double kStepReach = 0.4;
// back_within_energy's share: bisected to 2^-16, far below a written digit of a slide.
constexpr int kBackShareBits = 16;

// The state of the map: every chart node's point (the movable ones follow the slide), per movable
// vertex where its point lies, and the slid patch (local ids, the others at the frame).
struct MapState {
  Positions2 node_uv;
  std::vector<ChartPoint> where;
  Positions3 x;
};

// The pass's targets: per patch triangle s R_t, R_t the polar factor of the slid J_t, and its
// weight w c_t, c_t the crush weight (0 without a rest shape or for a J crushed to a line).
struct PassTargets {
  std::vector<Mat32> target;
  std::vector<double> weight;
};

PassTargets fitted_targets(const ArapTriangles& mesh, const Positions3& x, double s,
                           const std::vector<Vec3>& normals) {
  PassTargets out{std::vector<Mat32>(mesh.count, Mat32::Zero()),
                  std::vector<double>(mesh.count, 0.0)};
  for (Index t = 0; t < mesh.count; ++t) {
    const Eigen::Matrix2d& D = mesh.rest_inverse[t];
    if (!has_rest_shape(D)) continue;
    const SingularFrame f =
        singular_frame(deformation_gradient(x, mesh.triangles[t], D), normals[t]);
    if (!f.found) continue;
    out.weight[t] = mesh.weight * smoothstep(f.s2 / (kCrushed * f.s1));
    out.target[t] = s * (f.u1 * f.v1.transpose() + f.u2 * f.v2.transpose());
  }
  return out;
}

// The gradient per patch vertex of sum_t weight_t |J_t - target_t|^2 at `x`.
void target_gradient(const ArapTriangles& mesh, const PassTargets& targets, const Positions3& x,
                     Positions3& gradient) {
  gradient.assign(x.size(), Vec3::Zero());
  for (Index t = 0; t < mesh.count; ++t) {
    if (targets.weight[t] == 0) continue;
    const Triangle& tri = mesh.triangles[t];
    const Eigen::Matrix2d& D = mesh.rest_inverse[t];
    const Mat32 dE = 2 * targets.weight[t] * (deformation_gradient(x, tri, D) - targets.target[t]);
    const std::array<Vec2, 3> G = gradient_rows(D);
    for (int k = 0; k < 3; ++k) gradient[tri[k]] += dE * G[k];
  }
}

// Vertex i's tangent coordinates, regularised: S^T S = T^T T + kTangentFloor trace I, Q = T S^-1.
TangentFrame map_tangent_frame(const Mat32& T) {
  TangentFrame out;
  out.crushed = false;
  Eigen::Matrix2d M = T.transpose() * T;
  const double trace = M.trace();
  if (!(trace > 0) || !std::isfinite(trace)) {
    out.S_inverse.setZero();
    return out;
  }
  M.diagonal().array() += kTangentFloor * trace;
  const Eigen::Matrix2d S = M.llt().matrixU();
  out.S_inverse = S.inverse();
  out.Q = T * out.S_inverse;
  return out;
}

// K_ii per movable vertex.
std::vector<double> diagonal(const ElasticMetric& metric) {
  std::vector<double> out(metric.size(), 0.0);
  for (Index i = 0; i < metric.size(); ++i)
    for (Index e = metric.start[i]; e < metric.start[i + 1]; ++e)
      if (metric.column[e] == i) out[i] = metric.value[e];
  return out;
}

// A vertex's damping (kDamping): K_ii (I - Q^T Q) kDamping plus the metric's shift.
Eigen::Matrix2d step_damping(const ElasticMetric& metric, double stiffness,
                             const TangentFrame& frame) {
  return kDamping * stiffness * (Eigen::Matrix2d::Identity() - frame.Q.transpose() * frame.Q) +
         metric.shift * Eigen::Matrix2d::Identity();
}

// (Q^T (K x I3) Q + diag(damping)) p.
void apply_damped(const ElasticMetric& metric, const std::vector<TangentFrame>& frame,
                  const std::vector<Eigen::Matrix2d>& damping, const Positions2& p,
                  Positions3& motion, Positions2& out) {
  const Index m = metric.size();
  for (Index j = 0; j < m; ++j) motion[j] = frame[j].Q * p[j];
  for (Index i = 0; i < m; ++i) {
    Vec3 sum = Vec3::Zero();
    for (Index e = metric.start[i]; e < metric.start[i + 1]; ++e)
      sum += metric.value[e] * motion[metric.column[e]];
    out[i] = frame[i].Q.transpose() * sum + damping[i] * p[i];
  }
}

// The pass's chart step: `iterations` conjugate gradients from zero on the damped Gauss-Newton
// system in tangent coordinates, preconditioned by the bind's factor; d_i = S_i^-1 xi_i. Only an
// exactly solved system stops early (then every later iterate is the same).
Positions2 map_step(const ElasticMetric& metric, const std::vector<TangentFrame>& frames,
                    const Positions3& gradient, const std::vector<Eigen::Matrix2d>& damping,
                    int iterations, DirectionWork& work, int& done) {
  const Index m = metric.size();
  Positions2 &r = work.r, &x = work.x;
  r.resize(m);
  work.motion.resize(m);
  for (Index i = 0; i < m; ++i) r[i] = -(frames[i].Q.transpose() * gradient[i]);
  done += conjugate_gradients(
      work, iterations, [&](Positions2& z) { cholesky_solve(metric.factor, z, work.permuted); },
      [&](const Positions2& p, Positions2& Ap) {
        apply_damped(metric, frames, damping, p, work.motion, Ap);
      },
      [](const Positions2&) { return true; });
  Positions2 d(m);
  for (Index i = 0; i < m; ++i) d[i] = frames[i].S_inverse * x[i];
  return d;
}

// Twice the signed chart area of triangle t at node points `uv`.
double chart_area(const Triangle& t, const Positions2& uv) {
  return cross2(uv[t[1]] - uv[t[0]], uv[t[2]] - uv[t[0]]);
}

// The smallest altitude of a triangle with corners a, b, c and twice-area `area` (0 when the area
// is not positive): twice the area over its longest edge.
template <class V>
double smallest_altitude(const V& a, const V& b, const V& c, double area) {
  const double longest =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return longest > 0 && area > 0 ? area / std::sqrt(longest) : 0.0;
}

// Per movable vertex the share of its step `d` a pass takes (T: the vertices' Jacobians). Per patch
// triangle and edge the step's strain: the change it makes to the edge over the triangle's
// smallest altitude, in the chart and in 3D facing its frame triangle (T d for 3D; a corner that
// does not move changes nothing). While every edge of a triangle changes by less than half its
// smallest altitude, no corner crosses the line through the other two: the triangle does not
// fold. A vertex takes (1 + sum x^4)^(-1/4) of its step, the sum over every strain x of its
// triangles' edges, over kStepReach, in both spaces: nearly all of it where the step is smooth, a
// shrinking share where it would crush a triangle, and the largest strain it leaves is below the
// reach. A smooth function of the strains (a largest strain would kink the share where its
// argument changes hands: a kink in time). A step that moves a region as a whole strains
// nothing, however long (the bind's smooth modes on a large patch).
std::vector<double> step_shares(const ElasticSetup& setup, const FrameSurface& surface,
                                const MapState& state, const Positions2& d,
                                const std::vector<Mat32>& T) {
  const Chart& chart = setup.chart;
  // Per movable vertex the sum of its triangles' edge strains to the fourth power (over no reach).
  std::vector<double> strain4(setup.movable.size(), 0.0);
  const auto& u = state.node_uv;
  const auto& x = state.x;
  const auto over = [](double change, double altitude) {
    return change == 0 ? 0.0 : altitude > 0 ? change / altitude : INFINITY;
  };
  for (Index t = 0; t < chart.patch_triangle_count; ++t) {
    const Triangle& tri = chart.triangles[t];
    std::array<Vec2, 3> du;
    std::array<Vec3, 3> dx;
    bool moves = false;
    for (int k = 0; k < 3; ++k) {
      const Index i = setup.movable_slot[tri[k]];
      du[k] = i >= 0 ? d[i] : Vec2::Zero();
      dx[k] = i >= 0 ? Vec3(T[i] * d[i]) : Vec3::Zero();
      moves = moves || i >= 0;
    }
    if (!moves) continue;
    const double chart_altitude =
        smallest_altitude(u[tri[0]], u[tri[1]], u[tri[2]], chart_area(tri, u));
    const Vec3& n = surface.normals[t];
    const double nn = n.norm();
    const double space_altitude =
        nn > 0 ? smallest_altitude(x[tri[0]], x[tri[1]], x[tri[2]],
                                   (x[tri[1]] - x[tri[0]]).cross(x[tri[2]] - x[tri[0]]).dot(n) / nn)
               : 0.0;
    double e4 = 0;
    for (int k = 0; k < 3; ++k) {
      const double a = over((du[(k + 1) % 3] - du[k]).norm(), chart_altitude);
      const double b = nn > 0 ? over((dx[(k + 1) % 3] - dx[k]).norm(), space_altitude) : 0.0;
      e4 += a * a * a * a + b * b * b * b;
    }
    for (Index v : tri)
      if (const Index i = setup.movable_slot[v]; i >= 0) strain4[i] += e4;
  }
  constexpr double reach4 = kStepReach * kStepReach * kStepReach * kStepReach;
  std::vector<double> share(strain4.size());
  for (size_t i = 0; i < strain4.size(); ++i) {
    const double r4 = strain4[i] / reach4;
    share[i] = std::isfinite(r4) ? 1 / std::sqrt(std::sqrt(1 + r4)) : 0.0;
  }
  return share;
}

// The state after the step `d` from `from`, each vertex taking its share (step_shares).
void limited_step(const ElasticSetup& setup, const FrameSurface& surface,
                  const std::vector<Mat32>& T, const MapState& from, const Positions2& d,
                  MapState& to) {
  const std::vector<double> share = step_shares(setup, surface, from, d, T);
  to = from;
  for (size_t i = 0; i < setup.movable.size(); ++i) {
    if (share[i] == 0) continue;
    const Index v = setup.movable[i];
    to.node_uv[v] = from.node_uv[v] + share[i] * d[i];
    to.where[i] = locate_in_chart(setup.chart, to.node_uv[v], from.where[i].triangle);
    to.x[v] = surface_point(surface, to.where[i]);
  }
}

// The state `share` of the way from the frame (every movable vertex at its chart node) to `slid`
// in the chart.
void part_way(const ElasticSetup& setup, const FrameSurface& surface, const MapState& slid,
              double share, MapState& to) {
  to = slid;
  for (size_t i = 0; i < setup.movable.size(); ++i) {
    const Index v = setup.movable[i];
    const Vec2& node = setup.chart.uv[v];
    to.node_uv[v] = node + share * (slid.node_uv[v] - node);
    to.where[i] = locate_in_chart(setup.chart, to.node_uv[v], slid.where[i].triangle);
    to.x[v] = surface_point(surface, to.where[i]);
  }
}

// A map whose passes end above the frame's energy (its steps are Gauss-Newton steps, not a
// descent: it can, on a frame near rest) goes back towards the frame as far as the energy needs:
// the share of the way kept bisected to kBackShareBits bits between the frame (0, its own energy)
// and the slide (1, above it). The share is a continuous function of the frame where the energy
// crosses the frame's once along the way. Returns how many vertices went back (0: none).
int back_within_energy(const ElasticSetup& setup, const FrameSurface& surface,
                       const ArapTriangles& mesh, double scale, double energy_before,
                       MapState& slid, double& energy_after) {
  if (energy_after <= energy_before) return 0;
  double below = 0, above = 1;
  MapState trial;
  for (int bit = 0; bit < kBackShareBits; ++bit) {
    const double share = 0.5 * (below + above);
    part_way(setup, surface, slid, share, trial);
    (arap_energy(mesh, trial.x, scale, surface.normals) <= energy_before ? below : above) = share;
  }
  part_way(setup, surface, slid, below, trial);
  slid = std::move(trial);
  energy_after = below > 0 ? arap_energy(mesh, slid.x, scale, surface.normals) : energy_before;
  return static_cast<int>(setup.movable.size());
}

}  // namespace

double smoothstep(double x) {
  const double t = std::clamp(x, 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

std::vector<Mat32> vertex_jacobians(const FrameSurface& surface) {
  const Chart& chart = surface.chart;
  const Index n = static_cast<Index>(chart.corner_start.size()) - 1;
  std::vector<Mat32> field(n, Mat32::Zero());
  for (Index v = 0; v < n; ++v) {
    double area = 0;
    for (Index k = chart.corner_start[v]; k < chart.corner_start[v + 1]; ++k) {
      const Index t = chart.corner_triangles[k];
      const double a = chart_area(chart.triangles[t], chart.uv);
      field[v] += a * surface_jacobian(surface, t);
      area += a;
    }
    if (area > 0) field[v] /= area;
  }
  return field;
}

Mat32 blended_jacobian(const Chart& chart, const std::vector<Mat32>& field, const ChartPoint& p) {
  const Triangle& tri = chart.triangles[p.triangle];
  return p.weight[0] * field[tri[0]] + p.weight[1] * field[tri[1]] + p.weight[2] * field[tri[2]];
}

int map_step_budget(const ElasticSetup& setup, const Positions3& bind) {
  const ElasticMetric& metric = setup.metric;
  const Index m = metric.size();
  if (m == 0) return kMapStepIterations;
  const FrameSurface surface = frame_surface(setup.chart, bind);
  const std::vector<Mat32> field = vertex_jacobians(surface);
  const std::vector<double> stiffness = diagonal(metric);
  std::vector<TangentFrame> frames(m);
  std::vector<Eigen::Matrix2d> damping(m);
  for (Index i = 0; i < m; ++i) {
    frames[i] = map_tangent_frame(field[setup.movable[i]]);
    damping[i] = step_damping(metric, stiffness[i], frames[i]);
  }
  // The right side: K y per coordinate, y a fixed pseudo-random field in [-1/2, 1/2]^3 (every
  // mode of the metric, the stiffest included).
  Positions3 y(m), gradient(m, Vec3::Zero());
  for (Index i = 0; i < m; ++i)
    for (int c = 0; c < 3; ++c) {
      const auto k = static_cast<std::uint64_t>(i) * 3 + static_cast<std::uint64_t>(c);
      y[i][c] = static_cast<std::uint32_t>(k * 2654435761u) / 4294967296.0 - 0.5;
    }
  for (Index i = 0; i < m; ++i)
    for (Index e = metric.start[i]; e < metric.start[i + 1]; ++e)
      gradient[i] += metric.value[e] * y[metric.column[e]];
  double start = 0;
  for (Index i = 0; i < m; ++i) start += (frames[i].Q.transpose() * gradient[i]).squaredNorm();
  DirectionWork work;
  int budget = kMapStepIterations;
  for (; budget < kMaxMapStepIterations; budget *= 2) {
    int done = 0;
    map_step(metric, frames, gradient, damping, budget, work, done);
    if (dot(work.r, work.r) <= kMapStepResidual * kMapStepResidual * start) break;
  }
  return budget;
}

void smooth_map(const ElasticSetup& setup, const FrameSurface& surface, const SmoothMapRun& run,
                ElasticResult& result) {
  const Chart& chart = setup.chart;
  const Index m = static_cast<Index>(setup.movable.size());
  const ArapTriangles mesh = arap_triangles(setup);
  const ElasticMetric& metric = setup.metric;
  const std::vector<Mat32> field = vertex_jacobians(surface);
  const std::vector<double> stiffness = diagonal(metric);
  std::vector<Eigen::Matrix2d> damping(m);
  MapState state{chart.uv, std::vector<ChartPoint>(m), surface.frame};
  for (Index i = 0; i < m; ++i) state.where[i] = at_node(chart, setup.movable[i]);
  MapState next;
  Positions3 gradient, g_movable(m);
  std::vector<Mat32> T(m);
  std::vector<TangentFrame> frames(m);
  DirectionWork work;
  for (int pass = 0; pass < run.passes; ++pass) {
    const PassTargets targets = fitted_targets(mesh, state.x, result.scale, surface.normals);
    target_gradient(mesh, targets, state.x, gradient);
    for (Index i = 0; i < m; ++i) {
      g_movable[i] = gradient[setup.movable[i]];
      T[i] = blended_jacobian(chart, field, state.where[i]);
      frames[i] = map_tangent_frame(T[i]);
      damping[i] = step_damping(metric, stiffness[i], frames[i]);
    }
    const Positions2 d = map_step(metric, frames, g_movable, damping, run.step_iterations, work,
                                  result.solver_iterations);
    ++result.solves;
    for (const Vec2& di : d)
      if (!di.allFinite()) throw Error(ErrorKind::Numeric, "a pass's step is not finite");
    limited_step(setup, surface, T, state, d, next);
    std::swap(state, next);
    ++result.iterations;
  }
  result.energy_after = arap_energy(mesh, state.x, result.scale, surface.normals);
  result.held += back_within_energy(setup, surface, mesh, result.scale, result.energy_before, state,
                                    result.energy_after);
  for (Index i = 0; i < m; ++i) {
    const Index v = setup.movable[i];
    result.uv[i] = state.node_uv[v];
    result.where[i] = state.where[i];
    result.position[i] = state.x[v];
  }
}

}  // namespace skinslide
