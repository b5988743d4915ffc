// The map's continuity (lib/elastic/README.md "The map"): a slide is a continuous function of its
// frame, and a gentle one. 1e-12 of noise on a frame moves the slide by round-off; a bend swept
// in small steps moves the slide by a small share of the frame's step. The search (--solver
// search) steps five times further in the same sweep: its decisions jump.
#include "elastic/smooth_map.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "helpers/meshes.h"
#include "mesh/measures.h"
#include "pipeline/bind_setup.h"
#include "pipeline/slide_frame.h"
#include "helpers/samples.h"

namespace skinslide {
namespace {

// A 12 x 12 grid with a hole, swung about the y axis at x = 6 by `angle` with a twist of a
// quarter of it about the x axis, the skin over the joint stretched on top.
PolyMesh bind_grid() { return test::quad_grid_with_holes(12, 12, {40, 41, 52, 53}); }

Positions3 swung(const Positions3& bind, double angle) {
  Positions3 out = bind;
  for (Vec3& p : out) {
    const double x = p.x() - 6;
    if (x <= 0) continue;
    const double a = angle * std::min(x / 2, 1.0);  // the joint bends over two units
    const double twist = 0.25 * a * (p.y() - 6) / 6;
    const double r = x * (1 + 0.2 * std::exp(-x));
    p = Vec3(6 + r * std::cos(a), p.y() + 0.3 * twist, r * std::sin(a) + twist);
  }
  return out;
}

double mean_edge(const PolyMesh& mesh) {
  double total = 0;
  int count = 0;
  for (Index f = 0; f < mesh.face_count(); ++f) {
    const Index* v = mesh.face_begin(f);
    const Index n = mesh.face_size(f);
    for (Index k = 0; k < n; ++k) {
      total += (mesh.positions[v[k]] - mesh.positions[v[(k + 1) % n]]).norm();
      ++count;
    }
  }
  return total / count;
}

double max_distance(const Positions3& a, const Positions3& b) {
  double out = 0;
  for (size_t v = 0; v < a.size(); ++v) out = std::max(out, (a[v] - b[v]).norm());
  return out;
}

Positions3 slid(const BindSetup& setup, const Positions3& frame) {
  return apply_slide(frame, slide_frame(setup, frame).slid);
}

// The largest ratio, over a sweep of the swing from 0.4 to 1.6 in `steps` steps, of a step of
// the slide (a vertex's slid position less its frame position) to the frame's largest vertex
// step.
double sweep_gain(const BindSetup& setup, const PolyMesh& mesh, int steps) {
  double worst = 0;
  Positions3 frame_before = swung(mesh.positions, 0.4);
  Positions3 before = slid(setup, frame_before);
  for (int k = 1; k <= steps; ++k) {
    const Positions3 frame = swung(mesh.positions, 0.4 + 1.2 * k / steps);
    const Positions3 out = slid(setup, frame);
    Positions3 slide = out, slide_before = before;
    for (size_t v = 0; v < out.size(); ++v) {
      slide[v] -= frame[v];
      slide_before[v] -= frame_before[v];
    }
    worst = std::max(worst, max_distance(slide, slide_before) / max_distance(frame, frame_before));
    before = out;
    frame_before = frame;
  }
  return worst;
}

TEST(SmoothMap, NoiseOfTheFrameMovesTheSlideByRoundOff) {
  const PolyMesh mesh = bind_grid();
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{});
  const double edge = mean_edge(mesh);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (double angle : {0.8, 1.4}) {
    const Positions3 frame = swung(mesh.positions, angle);
    const Positions3 out = slid(setup, frame);
    ASSERT_GT(max_distance(out, frame), 0.05 * edge) << "the frame slides";
    for (int seed = 0; seed < 3; ++seed) {
      Positions3 noisy = frame;
      for (Vec3& p : noisy) p += 1e-12 * p.norm() * Vec3(unit(rng), unit(rng), unit(rng));
      EXPECT_LT(max_distance(slid(setup, noisy), out), 1e-6 * edge) << "angle " << angle;
    }
  }
}

TEST(SmoothMap, ASweptSwingMovesNoVertexMuchMoreThanTheFrame) {
  const PolyMesh mesh = bind_grid();
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{});
  EXPECT_LT(sweep_gain(setup, mesh, 100), 0.2);
}

TEST(SmoothMap, TheSearchStepsFurtherWhereTheMapDoesNot) {
  // The test above can fail: the search's line search, holds and tolerance stop step (0.44 of
  // the frame's step here, the map 0.084).
  const PolyMesh mesh = bind_grid();
  ElasticOptions search;
  search.solver = ElasticSolver::Search;
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, search);
  EXPECT_GT(sweep_gain(setup, mesh, 100), 0.3);
}

TEST(SmoothMap, TheVertexJacobianFieldIsContinuousAcrossEdges) {
  const PolyMesh mesh = bind_grid();
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{});
  const ElasticSetup& elastic = *test::elastic(setup).patches[0];
  const Patch& patch = setup.patches[0];
  Positions3 frame;
  for (Index v : patch.vertices) frame.push_back(swung(mesh.positions, 1.0)[v]);
  const FrameSurface surface = frame_surface(elastic.chart, frame);
  const std::vector<Mat32> field = vertex_jacobians(surface);
  const Chart& chart = elastic.chart;
  int edges = 0, kinks = 0;
  for (Index t = 0; t < chart.patch_triangle_count; ++t)
    for (int k = 0; k < 3; ++k) {
      const Index nb = chart.neighbour[t][k];
      if (nb < 0 || nb >= chart.patch_triangle_count) continue;
      // The point a third of the way along the edge opposite corner k, seen from both sides.
      const Index a = chart.triangles[t][(k + 1) % 3], b = chart.triangles[t][(k + 2) % 3];
      ChartPoint here{t, {0, 0, 0}}, there{nb, {0, 0, 0}};
      for (int c = 0; c < 3; ++c) {
        here.weight[c] = chart.triangles[t][c] == a   ? 2.0 / 3
                         : chart.triangles[t][c] == b ? 1.0 / 3
                                                      : 0;
        there.weight[c] = chart.triangles[nb][c] == a   ? 2.0 / 3
                          : chart.triangles[nb][c] == b ? 1.0 / 3
                                                        : 0;
      }
      EXPECT_LT(
          (blended_jacobian(chart, field, here) - blended_jacobian(chart, field, there)).norm(),
          1e-12);
      // The facets' own Jacobians differ there: the field is what makes the step continuous.
      kinks += (surface_jacobian(surface, t) - surface_jacobian(surface, nb)).norm() > 1e-3;
      ++edges;
    }
  EXPECT_GT(edges, 100);
  EXPECT_GT(kinks, 10) << "the swing bends the facets";
  EXPECT_DOUBLE_EQ(smoothstep(-1), 0);
  EXPECT_DOUBLE_EQ(smoothstep(0.5), 0.5);
  EXPECT_DOUBLE_EQ(smoothstep(2), 1);
}

}  // namespace
}  // namespace skinslide
