#include "elastic/window_mean.h"

#include <algorithm>

#include "core/check.h"
#include "elastic/line_search.h"
#include "elastic/surface_map.h"

namespace skinslide {
namespace {

// Rule 12's steps back towards a vertex's own relaxed point: quarters of the way.
constexpr int kQuarters = 4;

// Puts movable vertex i at chart point u, on the frame's facets.
void place(const ElasticSetup& setup, const Positions3& frame, ElasticResult& r, size_t i,
           const Vec2& u) {
  r.uv[i] = u;
  r.where[i] = locate_in_chart(setup.chart, u, r.where[i].triangle);
  r.position[i] = facet_point(setup.chart, frame, r.where[i]);
}

// The patch's positions with the movable vertices at r's.
Positions3 written_positions(const ElasticSetup& setup, const Positions3& frame,
                             const ElasticResult& r) {
  Positions3 x = frame;
  for (size_t i = 0; i < setup.movable.size(); ++i) x[setup.movable[i]] = r.position[i];
  return x;
}

// Rule 12: the moving corners of slid triangles that fold go back towards their own relaxed
// points by a quarter of the way at a time, until none folds; at the whole way a corner is at
// its own point, and where all of a triangle's are, it does not fold (relax.h's guarantees).
// Returns how many vertices moved back. A quarter at a time keeps what a corner gives up of the
// mean small: a corner sent back whole jumps by the jitter the window takes out (CesiumMan's
// knees: jitter max 0.29 bind edges a frame sent back whole, 0.15 by quarters, 0.084 unchecked
// with 3 triangles turned).
int return_folded(const ElasticSetup& setup, const Positions3& frame, const ElasticResult& own,
                  const Positions2& mean, ElasticResult& r) {
  const Chart& chart = setup.chart;
  std::vector<int> quarters(setup.movable.size(), 0);  // how far back, in quarters of the way
  for (bool any = true; any;) {
    any = false;
    const Positions3 x = written_positions(setup, frame, r);
    std::vector<char> fold_corner(setup.movable.size(), 0);
    for (Index t = 0; t < chart.patch_triangle_count; ++t) {
      const Triangle& tri = chart.triangles[t];
      if (!slid_triangle_folds(chart, setup.movable_slot, r.uv, frame, x, tri)) continue;
      for (Index v : tri)
        if (const Index i = setup.movable_slot[v]; i >= 0 && quarters[i] < kQuarters)
          fold_corner[i] = 1;
    }
    for (size_t i = 0; i < quarters.size(); ++i) {
      if (!fold_corner[i]) continue;
      any = true;
      if (++quarters[i] == kQuarters) {
        r.uv[i] = own.uv[i];
        r.where[i] = own.where[i];
        r.position[i] = own.position[i];
      } else {
        const double back = static_cast<double>(quarters[i]) / kQuarters;
        place(setup, frame, r, i, mean[i] + back * (own.uv[i] - mean[i]));
      }
    }
  }
  return static_cast<int>(
      std::count_if(quarters.begin(), quarters.end(), [](int q) { return q > 0; }));
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
  ElasticResult r = own;
  for (size_t i = 0; i < mean.size(); ++i) place(setup, frame, r, i, mean[i]);
  r.window_returned = return_folded(setup, frame, own, mean, r);
  r.energy_after = elastic_energy(setup, written_positions(setup, frame, r), own.scale);
  // The relaxation's promise (never above the frame's energy) holds for what is written.
  if (!(r.energy_after <= own.energy_before)) {
    r = own;
    r.window_returned = static_cast<int>(own.uv.size());
  }
  return r;
}

}  // namespace skinslide
