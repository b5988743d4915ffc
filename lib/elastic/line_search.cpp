#include "elastic/line_search.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "core/check.h"
#include "elastic/blended_surface.h"
#include "mesh/measures.h"

namespace skinslide {
namespace {

// A vertex stops at this share of the way to the first fold of one of its triangles: close
// enough to use the room, far enough that the triangle keeps a usable shape.
constexpr double kFoldMargin = 0.8;
constexpr int kMaxHalvings = 40;
// Armijo's sufficient decrease: a share of the first-order change.
constexpr double kArmijo = 1e-4;
// A signed area whose quadratic coefficient is below this share of the others' is linear.
constexpr double kLinear = 1e-14;

// The patch triangles with a corner that the step moves, ascending: only they can fold or turn.
std::vector<Index> moving_triangles(const LineSearchPatch& patch, const StepCandidate& step) {
  const Chart& chart = patch.surface.chart;
  std::vector<char> moves(chart.patch_triangle_count, 0);
  for (size_t i = 0; i < step.d.size(); ++i) {
    if (step.d[i].isZero(0)) continue;
    const Index v = patch.movable[i];
    for (Index k = chart.corner_start[v]; k < chart.corner_start[v + 1]; ++k)
      moves[chart.corner_triangles[k]] = 1;
  }
  std::vector<Index> out;
  for (Index t = 0; t < chart.patch_triangle_count; ++t)
    if (moves[t]) out.push_back(t);
  return out;
}

// A slid vertex where it is written: on the frame's facets (the others at the frame).
Vec3 written(const LineSearchPatch& patch, const SlideState& s, Index v) {
  const Index i = patch.movable_slot[v];
  return i >= 0 ? surface_point(patch.surface, s.where[i]) : s.x[v];
}

// Slid triangle t folded over in the chart, or turned against its frame triangle (where that
// has area): where the relaxation sees it and, on a blended surface, where it is written too.
bool folds(const LineSearchPatch& patch, const SlideState& s, Index t) {
  const Triangle& tri = patch.surface.chart.triangles[t];
  const Vec3& frame_normal = patch.surface.normals[t];
  const Vec3 n = (s.x[tri[1]] - s.x[tri[0]]).cross(s.x[tri[2]] - s.x[tri[0]]);
  if (slid_triangle_folds(s.node_uv[tri[0]], s.node_uv[tri[1]], s.node_uv[tri[2]], n, frame_normal))
    return true;
  if (!patch.surface.blend) return false;
  const Vec3 p0 = written(patch, s, tri[0]);
  const Vec3 n_written = (written(patch, s, tri[1]) - p0).cross(written(patch, s, tri[2]) - p0);
  return turned_against(n_written, frame_normal);
}

// Trial state: every moving vertex a share of its step along; `share` per movable vertex.
class Trial {
 public:
  Trial(const LineSearchPatch& patch, const SlideState& from, const StepCandidate& step)
      : patch_(patch), from_(from), step_(step), state(from), share(step.d.size(), 0.0) {}

  // Back to the start (the arrays keep their memory).
  void reset() {
    state = from_;
    std::fill(share.begin(), share.end(), 0.0);
  }

  void move(size_t i, double amount) {
    const Index v = patch_.movable[i];
    share[i] = amount;
    const Vec2 uv = from_.node_uv[v] + amount * step_.d[i];
    state.node_uv[v] = uv;
    state.where[i] = locate_in_chart(patch_.surface.chart, uv, step_.entered[i]);
    state.on_node[i] = 0;
    state.x[v] = relaxed_point(patch_.surface, state.where[i], uv);
  }

  void restore(size_t i) {
    const Index v = patch_.movable[i];
    share[i] = 0;
    state.node_uv[v] = from_.node_uv[v];
    state.where[i] = from_.where[i];
    state.on_node[i] = from_.on_node[i];
    state.x[v] = from_.x[v];
  }

  // The moving corners of every folded triangle stay where they were, until none folds (a
  // triangle whose corners all stay is as it was: unfolded). Returns how many were held.
  Index hold_folds(const std::vector<Index>& triangles) {
    Index held = 0;
    for (bool any = true; any;) {
      any = false;
      for (Index t : triangles) {
        if (!folds(patch_, state, t)) continue;
        for (Index v : patch_.surface.chart.triangles[t])
          if (const Index i = patch_.movable_slot[v]; i >= 0 && share[i] > 0) {
            restore(i);
            ++held;
            any = true;
          }
      }
    }
    return held;
  }

 private:
  const LineSearchPatch& patch_;
  const SlideState& from_;
  const StepCandidate& step_;

 public:
  SlideState state;
  std::vector<double> share;
};

}  // namespace

bool slid_triangle_folds(const Vec2& a, const Vec2& b, const Vec2& c, const Vec3& slid_normal,
                         const Vec3& frame_normal) {
  return !(cross2(b - a, c - a) > 0) || turned_against(slid_normal, frame_normal);
}

bool slid_triangle_folds(const Chart& chart, const std::vector<Index>& movable_slot,
                         const Positions2& uv, const Positions3& frame, const Positions3& slid,
                         const Triangle& t) {
  const auto chart_point = [&](Index v) {
    const Index i = movable_slot[v];
    return i >= 0 ? uv[i] : chart.uv[v];
  };
  const Vec3 nf = (frame[t[1]] - frame[t[0]]).cross(frame[t[2]] - frame[t[0]]);
  const Vec3 ns = (slid[t[1]] - slid[t[0]]).cross(slid[t[2]] - slid[t[0]]);
  return slid_triangle_folds(chart_point(t[0]), chart_point(t[1]), chart_point(t[2]), ns, nf);
}

double fold_root(const Chart& chart, const Positions2& node_uv, const Positions2& node_d, Index t) {
  const Triangle& tri = chart.triangles[t];
  const Vec2 d0 = node_d[tri[0]], d1 = node_d[tri[1]] - d0, d2 = node_d[tri[2]] - d0;
  if (d1.isZero(0) && d2.isZero(0)) return INFINITY;
  const Vec2 e1 = node_uv[tri[1]] - node_uv[tri[0]], e2 = node_uv[tri[2]] - node_uv[tri[0]];
  const double a = cross2(d1, d2);
  const double b = cross2(e1, d2) + cross2(d1, e2);
  const double c = cross2(e1, e2);
  double root = INFINITY;
  if (std::abs(a) <= kLinear * (std::abs(b) + std::abs(c))) {
    if (b < 0) root = -c / b;
  } else {
    const double disc = b * b - 4 * a * c;
    if (disc >= 0) {
      // The two roots without cancellation.
      const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
      for (const double r : {q / a, q != 0 ? c / q : INFINITY})
        if (r > 0) root = std::min(root, r);
    }
  }
  return root;
}

void bound_folds(const LineSearchPatch& patch, const SlideState& state, StepCandidate& step) {
  const Chart& chart = patch.surface.chart;
  Positions2 node_d(chart.uv.size(), Vec2::Zero());
  for (size_t i = 0; i < step.d.size(); ++i) node_d[patch.movable[i]] = step.d[i];
  step.moving = moving_triangles(patch, step);
  step.fold_roots.resize(step.moving.size());
  step.fold_bound = INFINITY;
  for (size_t k = 0; k < step.moving.size(); ++k) {
    step.fold_roots[k] = fold_root(chart, state.node_uv, node_d, step.moving[k]);
    step.fold_bound = std::min(step.fold_bound, step.fold_roots[k]);
  }
  step.bounded = true;
}

LineSearchResult flip_free_line_search(const LineSearchPatch& patch, const SlideState& state,
                                       double energy, const std::vector<StepCandidate>& candidates,
                                       const std::function<double(const Positions3&)>& energy_at) {
  LineSearchResult out;
  out.energy = energy;
  for (size_t c = 0; c < candidates.size(); ++c) {
    const StepCandidate& step = candidates[c];
    SKINSLIDE_CHECK(step.bounded, "a step searched before its fold bound");
    const std::vector<Index>& triangles = step.moving;
    if (triangles.empty()) continue;
    const size_t m = step.d.size();
    double alpha = std::min(1.0, kFoldMargin * step.fold_bound);
    Trial trial(patch, state, step);
    for (int halving = 0; halving < kMaxHalvings && alpha > 0; ++halving, alpha *= 0.5) {
      if (halving > 0) trial.reset();
      for (size_t i = 0; i < m; ++i)
        if (!step.d[i].isZero(0)) trial.move(i, alpha);
      const Index held = trial.hold_folds(triangles);
      double slope = 0;
      for (size_t i = 0; i < m; ++i) slope += trial.share[i] * step.rise[i];
      if (!(slope < 0)) continue;
      const double e = energy_at(trial.state.x);
      if (!(std::isfinite(e) && e < energy && e <= energy + kArmijo * slope)) continue;
      if (!out.accepted || e < out.energy) {
        out.accepted = true;
        out.candidate = c;
        out.alpha = alpha;
        out.energy = e;
        out.held = held;
        out.state = std::move(trial.state);
      }
      break;
    }
  }
  return out;
}

}  // namespace skinslide
