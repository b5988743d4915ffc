#include "elastic/window_mean.h"

#include <algorithm>

#include "core/check.h"
#include "elastic/line_search.h"
#include "elastic/surface_map.h"

namespace skinslide {
namespace {

// Rule 12's way back is found by bisection to 2^-30 of the way: far below a written digit.
constexpr int kBisections = 30;
// A patch whose mean is above the frame's energy goes back by a share bisected to 2^-16: a
// 65536th of the way between two slides a fraction of an edge apart, each trial a whole patch.
constexpr int kEnergyBisections = 16;
// Rounds in which a folded triangle's corners go back only as far as it needs; a triangle still
// folded after them sends its moving corners the whole way (where all of its are, it is its own
// relaxation's, which does not fold), so the loop ends.
constexpr int kRounds = 8;

// Puts movable vertex i at chart point u, on the frame's facets.
void place(const ElasticSetup& setup, const Positions3& frame, ElasticResult& r, size_t i,
           const Vec2& u) {
  r.uv[i] = u;
  r.where[i] = locate_in_chart(setup.chart, u, r.where[i].triangle);
  r.position[i] = facet_point(setup.chart, frame, r.where[i]);
}

// Movable vertex i a share `back` of the way from the mean to its own relaxed point (at the
// whole way exactly its own).
void place_back(const ElasticSetup& setup, const Positions3& frame, const ElasticResult& own,
                const Positions2& mean, double back, size_t i, ElasticResult& r) {
  if (back >= 1) {
    r.uv[i] = own.uv[i];
    r.where[i] = own.where[i];
    r.position[i] = own.position[i];
  } else {
    place(setup, frame, r, i, mean[i] + back * (own.uv[i] - mean[i]));
  }
}

// The patch's positions with the movable vertices at r's.
Positions3 written_positions(const ElasticSetup& setup, const Positions3& frame,
                             const ElasticResult& r) {
  Positions3 x = frame;
  for (size_t i = 0; i < setup.movable.size(); ++i) x[setup.movable[i]] = r.position[i];
  return x;
}

// The share of the way back, at least `back`'s, from which slid triangle `tri` no longer folds
// when its moving corners go back that far: bisected between the state given (folded) and the
// whole way (unfolded). The share grows from 0 as a fold starts, so the written slide stays a
// continuous function of the frames where the shares are below 1.
double share_unfolding(const ElasticSetup& setup, const Positions3& frame, const ElasticResult& own,
                       const Positions2& mean, const std::vector<double>& back, const Triangle& tri,
                       ElasticResult& r, Positions3& x) {
  const auto folds_at = [&](double share) {
    for (Index v : tri)
      if (const Index i = setup.movable_slot[v]; i >= 0) {
        place_back(setup, frame, own, mean, std::max(back[i], share), i, r);
        x[v] = r.position[i];
      }
    return slid_triangle_folds(setup.chart, setup.movable_slot, r.uv, frame, x, tri);
  };
  double folded = 0, unfolded = 1;
  for (int k = 0; k < kBisections; ++k) {
    const double mid = 0.5 * (folded + unfolded);
    (folds_at(mid) ? folded : unfolded) = mid;
  }
  folds_at(0);  // the corners back where the state given has them
  return unfolded;
}

// Rule 12: the moving corners of slid triangles that fold go back towards their own relaxed
// points, each only as far as its triangles need, until none folds. Returns how many vertices
// moved back. Going back only as far as needed keeps the slide continuous where a fold starts:
// in fixed steps a corner jumps by a step's share of the jitter the window takes out
// (tests/bench/elastic.md "The window's ways back made continuous").
int return_folded(const ElasticSetup& setup, const Positions3& frame, const ElasticResult& own,
                  const Positions2& mean, ElasticResult& r) {
  const Chart& chart = setup.chart;
  std::vector<double> back(setup.movable.size(), 0.0);  // share of the way back
  for (int round = 0;; ++round) {
    Positions3 x = written_positions(setup, frame, r);
    std::vector<double> raised = back;
    bool any = false;
    for (Index t = 0; t < chart.patch_triangle_count; ++t) {
      const Triangle& tri = chart.triangles[t];
      if (!slid_triangle_folds(chart, setup.movable_slot, r.uv, frame, x, tri)) continue;
      any = true;
      const double share =
          round < kRounds ? share_unfolding(setup, frame, own, mean, back, tri, r, x) : 1.0;
      for (Index v : tri)
        if (const Index i = setup.movable_slot[v]; i >= 0) raised[i] = std::max(raised[i], share);
    }
    if (!any) break;
    back = std::move(raised);
    for (size_t i = 0; i < back.size(); ++i)
      if (back[i] > 0) place_back(setup, frame, own, mean, back[i], i, r);
  }
  return static_cast<int>(std::count_if(back.begin(), back.end(), [](double b) { return b > 0; }));
}

// The chart points a share of the way from `mean` towards own's.
Positions2 towards_own(const Positions2& mean, const ElasticResult& own, double share) {
  Positions2 out(mean.size());
  for (size_t i = 0; i < mean.size(); ++i) out[i] = mean[i] + share * (own.uv[i] - mean[i]);
  return out;
}

// Own's relaxation with the chart points `target` written instead, on the frame's facets, its
// folded triangles' corners gone back as far as they need, and the energy of what is written.
ElasticResult written_at(const ElasticSetup& setup, const Positions3& frame,
                         const ElasticResult& own, const Positions2& target) {
  ElasticResult r = own;
  for (size_t i = 0; i < target.size(); ++i) place(setup, frame, r, i, target[i]);
  r.window_returned = return_folded(setup, frame, own, target, r);
  r.energy_after = elastic_energy(setup, written_positions(setup, frame, r), own.scale);
  return r;
}

}  // namespace

Positions2 chart_point_mean(const std::vector<WindowFrame>& frames) {
  SKINSLIDE_CHECK(!frames.empty(), "a window holds its own frame");
  Positions2 mean(frames.front().uv->size(), Vec2::Zero());
  for (const WindowFrame& f : frames) {
    SKINSLIDE_CHECK(f.uv->size() == mean.size(), "a window's frames slide one patch");
    for (size_t i = 0; i < mean.size(); ++i) mean[i] += f.weight * (*f.uv)[i];
  }
  return mean;
}

ElasticResult window_mean(const ElasticSetup& setup, const Positions3& frame,
                          const ElasticResult& own, const Positions2& mean) {
  SKINSLIDE_CHECK(mean.size() == own.uv.size(), "one chart point a movable vertex");
  // The bind up to a rigid motion and a scale comes back as it is (rule 4), window or not: its
  // neighbours' slides would move it off its minimum, which has no energy.
  if (own.stop == ElasticStop::AtRest) return own;
  ElasticResult r = written_at(setup, frame, own, mean);
  // The relaxation's promise (never above the frame's energy) holds for what is written: the
  // whole patch goes back towards its own slide as far as the energy needs, bisected between
  // the mean (above) and its own slide (below). Sent back whole, a patch jumped by the very
  // jitter the window takes out wherever the frames in a window differ too much to share a mean
  // (tests/bench/elastic.md "The window's ways back made continuous").
  if (!(r.energy_after <= own.energy_before)) {
    double above = 0, below = 1;
    r = own;
    for (int k = 0; k < kEnergyBisections; ++k) {
      const double share = 0.5 * (above + below);
      ElasticResult m = written_at(setup, frame, own, towards_own(mean, own, share));
      if (m.energy_after <= own.energy_before) {
        below = share;
        r = std::move(m);
      } else {
        above = share;
      }
    }
    r.window_returned = static_cast<int>(own.uv.size());
  }
  return r;
}

}  // namespace skinslide
