#include "elastic/relax.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "core/check.h"
#include "core/error.h"
#include "core/number_format.h"
#include "elastic/line_search.h"
#include "elastic/smooth_map.h"
#include "elastic/stationarity.h"
#include "elastic/surface_map.h"

namespace skinslide {
namespace {

// Rule 4: a frame whose ARAP energy is at most this share of the bind area is the bind up to a
// rigid motion and a uniform scale; its energy is round-off.
constexpr double kAtRest = 1e-20;
// Rule 8: a step cut short is solved again with the culprits held at most this many times,
// holding at most max(16, a tenth of the movable vertices) in all.
constexpr int kMaxHoldRounds = 12;
constexpr Index kMinHoldBudget = 16;
constexpr Index kHoldBudgetShare = 10;
// Rule 10: a frame short of stationary whose directions went unsolved is relaxed again with a
// budget this many times larger, up to this many iterations (8 -> 32 -> 128).
constexpr int kBudgetGrowth = 4;
constexpr int kMaxDirectionIterations = 128;
// A direction that stopped at its budget with more than this share of its starting residual
// left is unsolved: the median over a frame's capped directions at the budget of 8, which
// separates the meshes where the bind's factor fails from the rest (tests/bench/elastic.md
// "Escalation").
constexpr double kUnsolvedResidual = 0.1;

// One patch's relaxation in one frame, in named phases: the rotations of a round
// (fit_rotations), then steps: the Jacobians of the model, the direction (with holds where
// triangles cut it short), the flip-free line search.
class Relaxation {
 public:
  Relaxation(const ElasticSetup& setup, const FrameSurface& surface, double scale,
             ElasticResult& result)
      : setup_(setup),
        mesh_(arap_triangles(setup)),
        surface_(surface),
        s_(scale),
        result_(result),
        patch_{surface, setup.movable, setup.movable_slot},
        m_(static_cast<Index>(setup.movable.size())) {
    state_.node_uv = setup.chart.uv;
    state_.where.resize(m_);
    state_.on_node.assign(m_, 1);
    state_.x = surface.frame;
    for (Index i = 0; i < m_; ++i) state_.where[i] = at_node(setup.chart, setup.movable[i]);
  }

  const SlideState& state() const { return state_; }
  double energy() const { return E_; }
  bool failed() const { return failed_; }
  // The conjugate-gradient budget of every later direction.
  void set_direction_budget(int iterations) {
    solve_.max_iterations = iterations;
    capped_residuals_.clear();
  }
  int direction_budget() const { return solve_.max_iterations; }
  // Whether the directions since the budget was set went unsolved: most of those that stopped at
  // the budget left more than kUnsolvedResidual of their starting residual.
  bool directions_unsolved() {
    if (capped_residuals_.empty()) return false;
    const auto middle = capped_residuals_.begin() + capped_residuals_.size() / 2;
    std::nth_element(capped_residuals_.begin(), middle, capped_residuals_.end());
    return *middle > kUnsolvedResidual;
  }

  // ARAP's local step: the rotations nearest the slid patch, held for the round. Rule 6's eased
  // round (ElasticOptions::ease_in) aims `share` of the way from the frame's own deformation
  // gradients to s R.
  void fit_rotations(double share = 1) {
    R_ = fitted_rotations(mesh_, state_.x, surface_.normals);
    if (share < 1)
      for (Index t = 0; t < mesh_.count; ++t) {
        const Eigen::Matrix2d& D = mesh_.rest_inverse[t];
        if (!has_rest_shape(D)) continue;
        const Mat32 own = deformation_gradient(surface_.frame, mesh_.triangles[t], D);
        R_[t] = (1 - share) * own / s_ + share * R_[t];
      }
    E_ = held_rotation_energy(mesh_, state_.x, s_, R_, &g_);
  }

  // Rule 10's first-order measure at the current state, for the rotations last fitted (which
  // minimise the energy there: g_ is the ARAP energy's own gradient).
  FirstOrderGain measure() const {
    return stationarity(surface_, setup_.movable, state_, g_, setup_.metric,
                        CurvatureInputs{mesh_, s_, setup_.movable_slot});
  }

  // One step: false when no step lowers the energy, or the direction could not be solved.
  bool step() {
    model_jacobians();
    frames_ = tangent_frames(T_);
    for (Index i = 0; i < m_; ++i) g_movable_[i] = g_[setup_.movable[i]];
    candidates_.clear();
    held_.clear();
    if (!add_candidate()) return false;
    if (!add_held_candidate()) return false;
    const auto energy_at = [&](const Positions3& x) {
      return held_rotation_energy(mesh_, x, s_, R_);
    };
    LineSearchResult searched = flip_free_line_search(patch_, state_, E_, candidates_, energy_at);
    if (!searched.accepted) return false;
    result_.held += searched.held;
    if (searched.candidate == 1)
      result_.held += static_cast<int>(std::count(held_.begin(), held_.end(), 1));
    state_ = std::move(searched.state);
    E_ = held_rotation_energy(mesh_, state_.x, s_, R_, &g_);
    return true;
  }

 private:
  // Per movable vertex the Jacobian the step is modelled with: the blended surface's where it
  // is; on the facets its chart triangle's, or at its own node (before it first moves) the
  // node's least-squares map.
  void model_jacobians() {
    T_.resize(m_);
    g_movable_.resize(m_);
    for (Index i = 0; i < m_; ++i) {
      const Index v = setup_.movable[i];
      if (surface_.blend)
        blended_point(surface_, state_.where[i].triangle, state_.node_uv[v], &T_[i]);
      else
        T_[i] = state_.on_node[i] ? node_jacobian(surface_, v)
                                  : surface_jacobian(surface_, state_.where[i].triangle);
    }
  }

  // The direction with the vertices in held_ held (none when empty), as a candidate.
  bool add_candidate() {
    StepDirection direction =
        held_.empty() ? step_direction(setup_.metric, frames_, g_movable_, held_, work_, solve_)
                      : held_direction(setup_.metric, frames_, g_movable_, held_, work_);
    result_.solver_iterations += direction.iterations;
    if (direction.capped) capped_residuals_.push_back(direction.residual);
    ++result_.solves;
    if (!direction.finite) {
      failed_ = true;
      return false;
    }
    // A blended surface has a Jacobian at the nodes too: the model's steps are the surface's.
    for (Index i = 0; i < m_ && !surface_.blend; ++i)
      if (state_.on_node[i] && !direction.d[i].isZero(0))
        direction.d[i] = redirected_from_node(surface_, setup_.movable[i], T_[i], direction.d[i]);
    candidates_.push_back(candidate(std::move(direction.d)));
    return true;
  }

  // A step that a few triangles cut short would leave the rest of the patch stuck: with those
  // triangles' vertices held, the step is solved again, until none cuts it short or the hold
  // budget is spent. The held step is the second candidate (the line search keeps the better).
  bool add_held_candidate() {
    held_.assign(m_, 0);
    Index budget = std::max<Index>(kMinHoldBudget, m_ / kHoldBudgetShare);
    for (int round = 0; round < kMaxHoldRounds; ++round) {
      const StepCandidate& step = candidates_.back();
      if (!(step.fold_bound < 1)) break;
      more_ = held_;
      Index added = 0;
      for (size_t k = 0; k < step.moving.size(); ++k)
        if (step.fold_roots[k] < 1)
          for (Index v : setup_.chart.triangles[step.moving[k]])
            if (const Index i = setup_.movable_slot[v]; i >= 0 && !more_[i]) {
              more_[i] = 1;
              ++added;
            }
      if (added == 0 || added > budget) break;
      budget -= added;
      std::swap(held_, more_);
      if (candidates_.size() == 2) candidates_.pop_back();
      if (!add_candidate()) return false;
    }
    return true;
  }

  // The step as it truly is: each vertex moves with the Jacobian of the triangle it enters (on a
  // blended surface, the smooth one where it is). If that step does not go down to first order
  // (on the facets the model's Jacobians, at a node or across a chart edge, are not the
  // surface's), the vertices whose energy would rise stay (held).
  StepCandidate candidate(Positions2 d) {
    StepCandidate out;
    out.entered.resize(m_);
    out.rise.resize(m_);
    double slope = 0;
    for (Index i = 0; i < m_; ++i) {
      const Index v = setup_.movable[i];
      out.entered[i] = entered_triangle(setup_.chart, state_.on_node[i] ? v : -1, state_.node_uv[v],
                                        state_.where[i].triangle, d[i]);
      out.rise[i] = surface_.blend ? g_[v].dot(T_[i] * d[i])
                                   : g_[v].dot(surface_jacobian(surface_, out.entered[i]) * d[i]);
      slope += out.rise[i];
    }
    if (!(slope < 0))
      for (Index i = 0; i < m_; ++i)
        if (!(out.rise[i] <= 0)) {
          d[i] = Vec2::Zero();
          out.entered[i] = state_.where[i].triangle;
          out.rise[i] = 0;
          ++result_.held;
        }
    out.d = std::move(d);
    bound_folds(patch_, state_, out);
    return out;
  }

  const ElasticSetup& setup_;
  const ArapTriangles mesh_;
  const FrameSurface& surface_;
  const double s_;
  ElasticResult& result_;
  const LineSearchPatch patch_;
  const Index m_;
  SlideState state_;
  std::vector<Mat32> R_;  // the rotations of the current round
  Positions3 g_;          // the held-rotation energy's gradient at state_.x
  double E_ = 0;          // the held-rotation energy at state_.x
  bool failed_ = false;
  DirectionSolve solve_;
  std::vector<double> capped_residuals_;  // |r| / |r_0| of the directions that hit the budget
  // A step's work arrays, kept from step to step.
  std::vector<Mat32> T_;  // the model's Jacobians
  std::vector<TangentFrame> frames_;
  Positions3 g_movable_;
  std::vector<char> held_, more_;
  std::vector<StepCandidate> candidates_;
  DirectionWork work_;
};

// Rule 6: the rounds of ARAP's local/global alternation, each relaxed until a step gains less
// than the tolerance; the first pass from the frame eases its first rounds' targets in
// (ElasticOptions::ease_in), a later pass starts from a relaxed state and aims fully. Returns how
// the last round ended.
ElasticStop relax_pass(Relaxation& relaxation, const ElasticOptions& options, bool from_frame,
                       ElasticResult& result) {
  ElasticStop last_round = ElasticStop::SmallGain;
  for (int round = 0; round < options.rotation_fits; ++round) {
    const bool eased = from_frame && round < options.ease_in;
    relaxation.fit_rotations(eased ? (round + 1.0) / (options.ease_in + 1.0) : 1.0);
    const double E_round = relaxation.energy();
    int it = 0;
    last_round = ElasticStop::IterationLimit;
    for (; it < options.max_iterations; ++it) {
      const double E_old = relaxation.energy();
      if (!relaxation.step()) {
        last_round = ElasticStop::NoStep;
        break;
      }
      ++result.iterations;
      if (E_old - relaxation.energy() < options.tolerance * E_round) {
        last_round = ElasticStop::SmallGain;
        break;
      }
    }
    if (relaxation.failed()) {
      last_round = ElasticStop::SolveFailed;
      break;
    }
  }
  return last_round;
}

// Rule 10: the passes and the stop. A frame the measure finds short of stationary, whose last
// round stalled (small gain) or ran out of steps (limit) while its directions went unsolved
// (directions_unsolved), is relaxed again, as many rounds from where it
// is, with a budget kBudgetGrowth times larger, up to kMaxDirectionIterations: where the
// frame's tangent planes turn against the bind's all over and slivers stiffen the metric (in
// sculpts and scans), the bind's factor is a poor preconditioner and 8 iterations leave steps
// too short to count (tests/bench/elastic.md "Escalation"). A frame that converges in the first
// pass, or whose directions were nearly solved, is not touched.
void relax_rounds(Relaxation& relaxation, const ElasticOptions& options, ElasticResult& result) {
  relaxation.set_direction_budget(DirectionSolve{}.max_iterations);
  ElasticStop last_round = relax_pass(relaxation, options, true, result);
  for (;;) {
    relaxation.fit_rotations();
    const FirstOrderGain gain = relaxation.measure();
    const double tolerance = options.convergence * result.energy_before;
    result.gain_left = gain.larger();
    if (result.gain_left <= tolerance && !relaxation.failed()) {
      result.stop = ElasticStop::Converged;
      return;
    }
    result.stop = last_round;
    // The escalation was tuned on the bind's metric alone: a frame it finds stationary is not
    // relaxed again, so that the curvature's reading changes the stop's name, not the slide (the
    // escalation on its reading: tests/bench/elastic.md "Honest stops: the first-order gain left").
    if (gain.bind_metric <= tolerance) return;
    const int budget = relaxation.direction_budget() * kBudgetGrowth;
    // A round at --max-iterations is escalated too: with unsolved directions its steps were
    // too short to count, however many it took (tests/bench/elastic.md "A round at its step
    // limit, escalated").
    const bool stalled =
        last_round == ElasticStop::SmallGain || last_round == ElasticStop::IterationLimit;
    if (!stalled || !relaxation.directions_unsolved() || budget > kMaxDirectionIterations) return;
    relaxation.set_direction_budget(budget);
    ++result.escalations;
    last_round = relax_pass(relaxation, options, false, result);
  }
}

// Rule 10's measure at a slid patch given as a result (the map's): every triangle's rotation fitted
// there, the ARAP energy's own gradient. Past `short_of` the patch has not converged whatever the
// curvature reads: the bind metric's reading is returned, a lower bound.
double gain_left_at(const ElasticSetup& setup, const FrameSurface& surface, double s,
                    const ElasticResult& result, double short_of) {
  const ArapTriangles mesh = arap_triangles(setup);
  SlideState state;
  state.node_uv = setup.chart.uv;
  state.x = surface.frame;
  state.where = result.where;
  state.on_node.resize(setup.movable.size());
  for (size_t i = 0; i < setup.movable.size(); ++i) {
    const Index v = setup.movable[i];
    state.node_uv[v] = result.uv[i];
    state.x[v] = result.position[i];
    state.on_node[i] = result.uv[i] == setup.chart.uv[v];
  }
  const std::vector<Mat32> R = fitted_rotations(mesh, state.x, surface.normals);
  Positions3 g;
  held_rotation_energy(mesh, state.x, s, R, &g);
  return stationarity(surface, setup.movable, state, g, setup.metric,
                      CurvatureInputs{mesh, s, setup.movable_slot}, short_of)
      .larger();
}

}  // namespace

const char* stop_name(ElasticStop stop) {
  switch (stop) {
    case ElasticStop::AtRest:
      return "at rest";
    case ElasticStop::Converged:
      return "converged";
    case ElasticStop::SmallGain:
      return "small gain";
    case ElasticStop::IterationLimit:
      return "limit";
    case ElasticStop::NoStep:
      return "no step";
    case ElasticStop::NoDescent:
      return "no descent";
    case ElasticStop::SolveFailed:
      return "solve failed";
    case ElasticStop::Passes:
      return "passes";
  }
  return "unknown";
}

ArapTriangles arap_triangles(const ElasticSetup& setup) {
  return ArapTriangles{setup.chart.triangles, setup.chart.patch_triangle_count, setup.rest_inverse,
                       setup.triangle_weight};
}

ElasticSetup elastic_setup(const Positions3& points, const std::vector<Triangle>& triangles,
                           const std::vector<std::vector<Index>>& loops, Index outer_loop,
                           const std::vector<Index>& movable, double blend) {
  ElasticSetup setup;
  setup.chart = disk_chart(points, triangles, loops, outer_loop);
  if (blend > 0) setup.blend = surface_blend(setup.chart, blend);
  setup.movable = movable;
  setup.movable_slot.assign(points.size(), -1);
  for (size_t i = 0; i < movable.size(); ++i)
    setup.movable_slot[movable[i]] = static_cast<Index>(i);
  setup.rest_inverse.resize(triangles.size());
  double area = 0;
  for (size_t t = 0; t < triangles.size(); ++t) {
    const Triangle& tri = triangles[t];
    setup.rest_inverse[t] = rest_inverse(points[tri[0]], points[tri[1]], points[tri[2]]);
    area += 0.5 * (points[tri[1]] - points[tri[0]]).cross(points[tri[2]] - points[tri[0]]).norm();
  }
  setup.bind_area = area;
  // Uniform weights: every triangle's stretch counts the same (small triangles are where skin
  // creases); the mean area only gives the energy the units of an area.
  setup.triangle_weight = triangles.empty() ? 0.0 : area / static_cast<double>(triangles.size());
  setup.metric =
      elastic_metric(arap_triangles(setup), setup.movable_slot, static_cast<Index>(movable.size()));
  setup.map_step_iterations = map_step_budget(setup, points);
  return setup;
}

double elastic_energy(const ElasticSetup& setup, const Positions3& x, double scale) {
  const auto& tris = setup.chart.triangles;
  std::vector<Vec3> normals(setup.chart.patch_triangle_count);
  for (size_t t = 0; t < normals.size(); ++t)
    normals[t] = (x[tris[t][1]] - x[tris[t][0]]).cross(x[tris[t][2]] - x[tris[t][0]]);
  return arap_energy(arap_triangles(setup), x, scale, normals);
}

void put_at_start(const ElasticSetup& setup, const Positions3& frame, ElasticResult& result) {
  const size_t m = setup.movable.size();
  result.uv.resize(m);
  result.where.resize(m);
  result.position.resize(m);
  for (size_t i = 0; i < m; ++i) {
    const Index v = setup.movable[i];
    result.uv[i] = setup.chart.uv[v];
    result.where[i] = at_node(setup.chart, v);
    result.position[i] = frame[v];
  }
}

ElasticResult relax_patch(const ElasticSetup& setup, const Positions3& frame,
                          const ElasticOptions& options) {
  const Chart& chart = setup.chart;
  const Index m = static_cast<Index>(setup.movable.size());
  ElasticResult result;
  put_at_start(setup, frame, result);
  if (m == 0) return result;
  const FrameSurface surface =
      frame_surface(chart, frame, setup.blend.edges.empty() ? nullptr : &setup.blend);
  const double s = setup.bind_area > 0 ? std::sqrt(surface.area / setup.bind_area) : 1.0;
  result.scale = s;
  const ArapTriangles mesh = arap_triangles(setup);
  result.energy_before = result.energy_after = arap_energy(mesh, frame, s, surface.normals);
  if (!std::isfinite(result.energy_before) || !std::isfinite(s))
    throw Error(ErrorKind::Numeric, "the frame's elastic energy is not finite");
  if (result.energy_before <= kAtRest * setup.bind_area) {
    result.stop = ElasticStop::AtRest;
    return result;
  }
  if (options.solver == ElasticSolver::Map) {
    smooth_map(setup, surface, SmoothMapRun{options.passes, setup.map_step_iterations}, result);
    const double tolerance = options.convergence * result.energy_before;
    result.gain_left = gain_left_at(setup, surface, s, result, tolerance);
    result.stop = result.gain_left <= tolerance ? ElasticStop::Converged : ElasticStop::Passes;
    for (Index i = 0; i < m; ++i)
      if (!result.position[i].allFinite())
        throw Error(ErrorKind::Numeric, "patch vertex " + std::to_string(setup.movable[i]) +
                                            ": the slid position is not finite");
    return result;
  }
  Relaxation relaxation(setup, surface, s, result);
  relax_rounds(relaxation, options, result);
  // The slid vertices are written on the frame's facets at their chart points (where a blended
  // surface's points are not; on the facets the relaxed points are the written ones).
  SlideState written;
  if (surface.blend) {
    written = relaxation.state();
    for (Index i = 0; i < m; ++i)
      written.x[setup.movable[i]] = surface_point(surface, written.where[i]);
  }
  const SlideState& slid = surface.blend ? written : relaxation.state();
  // Each round starts where the last ended, with the rotations that minimise the ARAP energy
  // there, and only lowers it: round-off aside, it cannot rise. A frame whose relaxation gained
  // nothing comes back unchanged.
  result.energy_after = arap_energy(mesh, slid.x, s, surface.normals);
  if (!(result.energy_after <= result.energy_before)) {
    put_at_start(setup, frame, result);
    result.energy_after = result.energy_before;
    result.stop = ElasticStop::NoDescent;
    ElasticResult scratch;
    Relaxation at_frame(setup, surface, s, scratch);
    at_frame.fit_rotations();
    result.gain_left = at_frame.measure().larger();
    return result;
  }
  for (Index i = 0; i < m; ++i) {
    const Index v = setup.movable[i];
    result.uv[i] = slid.node_uv[v];
    result.where[i] = slid.where[i];
    result.position[i] = slid.x[v];
    if (!result.position[i].allFinite())
      throw Error(ErrorKind::Numeric,
                  "patch vertex " + std::to_string(v) + ": the slid position is not finite");
  }
  return result;
}

}  // namespace skinslide
