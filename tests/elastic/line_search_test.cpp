// The elastic method's flip-free line search (lib/elastic/README.md rules 8-9): the fold root
// is exact on hand-made triangles; a step that would fold a triangle is cut at 0.8 of its root;
// a vertex whose triangle would turn against the frame stays; the energy falls.
#include "elastic/line_search.h"

#include <cmath>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "elastic/chart.h"

namespace skinslide {
namespace {

// One chart triangle (0,0) (1,0) (0,1) whose third corner moves by d.
double root_for(const Vec2& d) {
  Chart chart;
  chart.uv = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  chart.triangles = {{0, 1, 2}};
  const Positions2 node_d{Vec2::Zero(), Vec2::Zero(), d};
  return fold_root(chart, chart.uv, node_d, 0);
}

TEST(FoldRoot, ExactOnHandMadeSteps) {
  // The apex goes straight down onto the base line y = 0: area 0 after 1 / 2 of a step of 2.
  EXPECT_DOUBLE_EQ(root_for(Vec2(0, -2)), 0.5);
  // Sideways along the base's parallel the area stays: no root.
  EXPECT_TRUE(std::isinf(root_for(Vec2(3, 0))));
  // Away from the base: never folds.
  EXPECT_TRUE(std::isinf(root_for(Vec2(0.2, 1))));
  // Two corners moving: (1,0) -> (1,0) + a (-1, 1) and (0,1) -> (0,1) + a (1, -1) swap
  // through the diagonal: the signed area 1/2 (1 - 2a)... vanishes at a = 1/2.
  Chart chart;
  chart.uv = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  chart.triangles = {{0, 1, 2}};
  const Positions2 node_d{Vec2::Zero(), Vec2(-1, 1), Vec2(1, -1)};
  EXPECT_NEAR(fold_root(chart, chart.uv, node_d, 0), 0.5, 1e-15);
}

// A flat fan of two triangles in the chart and in 3D: (0,0) (2,0) (1,1) (1,-1), the movable
// vertex 2 at (1,1) on top. The energy is the height of vertex 2 above y = 0.5, squared: a step
// straight down (d = (0, -2)) would fold triangle 0 at alpha 1/2.
struct Fan {
  Chart chart;
  Positions3 frame;
  std::vector<Index> movable{2};
  std::vector<Index> movable_slot{-1, -1, 0, -1};
  Fan() {
    chart.uv = {Vec2(0, 0), Vec2(2, 0), Vec2(1, 1), Vec2(1, -1)};
    chart.triangles = {{0, 1, 2}, {0, 3, 1}};
    chart.patch_triangle_count = 2;
    chart.neighbour = {{-1, -1, 1}, {-1, -1, 0}};
    for (const Triangle& t : chart.triangles) {
      Eigen::Matrix2d E;
      E.col(0) = chart.uv[t[1]] - chart.uv[t[0]];
      E.col(1) = chart.uv[t[2]] - chart.uv[t[0]];
      chart.inverse_edges.push_back(E.inverse());
    }
    chart.corner_start = {0, 2, 4, 5, 6};
    chart.corner_triangles = {0, 1, 0, 1, 0, 1};
    for (const Vec2& uv : chart.uv) frame.push_back(Vec3(uv.x(), uv.y(), 0));
  }
  // Vertex 2 on its own node, the slid fan the frame.
  SlideState start() const {
    SlideState state;
    state.node_uv = chart.uv;
    state.where = {ChartPoint{0, {0, 0, 1}}};
    state.on_node = {1};
    state.x = frame;
    return state;
  }
};

TEST(FlipFreeLineSearch, CutsAFoldingStepShortAndLowersTheEnergy) {
  const Fan fan;
  const FrameSurface surface = frame_surface(fan.chart, fan.frame);
  const LineSearchPatch patch{surface, fan.movable, fan.movable_slot};
  const SlideState state = fan.start();
  const auto energy_at = [](const Positions3& x) { return std::pow(x[2].y() - 0.5, 2); };
  StepCandidate step;
  step.d = {Vec2(0, -2)};
  step.entered = {0};
  step.rise = {2 * (1 - 0.5) * -2};  // dE/dy times the step's y
  bound_folds(patch, state, step);
  EXPECT_EQ(step.moving, std::vector<Index>{0}) << "the moving vertex has one triangle";
  EXPECT_DOUBLE_EQ(step.fold_bound, 0.5);
  const LineSearchResult r =
      flip_free_line_search(patch, state, energy_at(state.x), {step}, energy_at);
  ASSERT_TRUE(r.accepted);
  EXPECT_DOUBLE_EQ(r.alpha, 0.4) << "0.8 of the fold root";
  EXPECT_NEAR(r.state.x[2].y(), 1 - 0.8, 1e-15);
  EXPECT_LT(r.energy, energy_at(state.x));
  EXPECT_EQ(r.held, 0);
}

TEST(FlipFreeLineSearch, NoStepWhenEveryShareRaisesTheEnergy) {
  const Fan fan;
  const FrameSurface surface = frame_surface(fan.chart, fan.frame);
  const LineSearchPatch patch{surface, fan.movable, fan.movable_slot};
  const SlideState state = fan.start();
  // Already at the minimum along x: any move raises the energy, whatever the slope claims.
  const auto energy_at = [](const Positions3& x) { return std::pow(x[2].x() - 1, 2); };
  StepCandidate step;
  step.d = {Vec2(0.1, 0)};
  step.entered = {0};
  step.rise = {-1};
  bound_folds(patch, state, step);
  const LineSearchResult r =
      flip_free_line_search(patch, state, energy_at(state.x), {step}, energy_at);
  EXPECT_FALSE(r.accepted);
  EXPECT_EQ(r.energy, energy_at(state.x));
}

}  // namespace
}  // namespace skinslide
