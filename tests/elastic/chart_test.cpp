// The elastic method's chart: injective, the outer loop on the circle, holes filled, and a walk
// that finds every point.
#include "elastic/chart.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "core/error.h"
#include "helpers/meshes.h"
#include "mesh/patches.h"

namespace skinslide {
namespace {

double signed_area(const Chart& c, Index t) {
  const Triangle& tri = c.triangles[t];
  const Vec2 e1 = c.uv[tri[1]] - c.uv[tri[0]], e2 = c.uv[tri[2]] - c.uv[tri[0]];
  return e1.x() * e2.y() - e1.y() * e2.x();
}

struct Disk {
  Positions3 points;
  std::vector<Triangle> triangles;
  std::vector<std::vector<Index>> loops;
  Index outer = 0;
};

// A grid patch (mesh ids = local ids: every grid vertex must be in a face) as fan triangles.
Disk grid_disk(const PolyMesh& mesh) {
  Disk d;
  d.points = mesh.positions;
  for (Index f = 0; f < mesh.face_count(); ++f) {
    const Index* v = mesh.face_begin(f);
    for (Index k = 0; k + 2 < mesh.face_size(f); ++k)
      d.triangles.push_back({v[0], v[k + 1], v[k + 2]});
  }
  const auto comps = patch_components(mesh, {test::all_faces(mesh)},
                                      [](Index f) { return "face " + std::to_string(f); });
  d.loops = comps.at(0).loops;
  size_t longest = 0;
  for (size_t l = 0; l < d.loops.size(); ++l)
    if (d.loops[l].size() > d.loops[longest].size()) longest = l;
  d.outer = static_cast<Index>(longest);
  return d;
}

TEST(Chart, AGridWithAHoleIsEmbeddedInjectively) {
  // Bend the grid out of its plane so that the mean-value weights are not the plane's.
  PolyMesh mesh = test::quad_grid_with_holes(8, 8, {27, 28, 35});
  for (Vec3& p : mesh.positions) p.z() = 0.3 * std::sin(p.x()) * std::cos(0.5 * p.y());
  const Disk d = grid_disk(mesh);
  ASSERT_EQ(d.loops.size(), 2u);
  const Chart c = disk_chart(d.points, d.triangles, d.loops, d.outer);
  EXPECT_FALSE(c.uniform_weights);
  ASSERT_EQ(c.patch_triangle_count, static_cast<Index>(d.triangles.size()));
  const size_t hole = d.loops[1 - d.outer].size();
  EXPECT_EQ(c.triangles.size(), d.triangles.size() + hole) << "a fill triangle per hole edge";
  EXPECT_EQ(c.uv.size(), d.points.size() + 1) << "one centre node per hole";
  for (Index t = 0; t < static_cast<Index>(c.triangles.size()); ++t)
    EXPECT_GT(signed_area(c, t), 0) << "triangle " << t;
  for (Index v : d.loops[d.outer])
    EXPECT_NEAR((c.uv[v] - Vec2(0.5, 0.5)).norm(), 0.5, 1e-15) << "outer vertex on the circle";
  for (size_t v = 0; v < c.uv.size(); ++v) {
    EXPECT_LE((c.uv[v] - Vec2(0.5, 0.5)).norm(), 0.5 + 1e-15);
  }
  // The patch triangles around each vertex are exactly those with it as a corner.
  for (Index v = 0; v < static_cast<Index>(d.points.size()); ++v)
    for (Index k = c.corner_start[v]; k < c.corner_start[v + 1]; ++k) {
      const Triangle& t = c.triangles[c.corner_triangles[k]];
      EXPECT_TRUE(t[0] == v || t[1] == v || t[2] == v);
    }
}

TEST(Chart, TheWalkFindsEveryPointOnAPatchTriangle) {
  const Disk d = grid_disk(test::quad_grid_with_holes(10, 10, {44, 45, 55}));
  const Chart c = disk_chart(d.points, d.triangles, d.loops, d.outer);
  std::mt19937 rng(0);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 2000; ++k) {
    const Vec2 p(u(rng), u(rng));
    const ChartPoint q = locate_in_chart(c, p, static_cast<Index>(k % c.patch_triangle_count));
    ASSERT_GE(q.triangle, 0);
    ASSERT_LT(q.triangle, c.patch_triangle_count) << "never a fill triangle";
    double sum = 0;
    for (double w : q.weight) {
      EXPECT_GE(w, 0);
      EXPECT_LE(w, 1);
      sum += w;
    }
    EXPECT_NEAR(sum, 1, 1e-15);
    const Triangle& t = c.triangles[q.triangle];
    const Vec2 back =
        q.weight[0] * c.uv[t[0]] + q.weight[1] * c.uv[t[1]] + q.weight[2] * c.uv[t[2]];
    // Inside the border polygon (40 vertices on the circle: its chords dip 1.5e-3 inside).
    const bool in_disk = (p - Vec2(0.5, 0.5)).norm() < 0.49;
    bool in_hole = false;
    for (Index tt = c.patch_triangle_count; tt < static_cast<Index>(c.triangles.size()); ++tt) {
      const auto w = chart_barycentric(c, tt, p);
      in_hole = in_hole || (w[0] > 1e-9 && w[1] > 1e-9 && w[2] > 1e-9);
    }
    if (in_disk && !in_hole) {
      EXPECT_LT((back - p).norm(), 1e-12) << "a point inside the patch is found exactly";
    }
  }
}

// A bent grid with three holes, large enough for the iterative solve (1 600 nodes).
Disk bent_grid_disk() {
  PolyMesh mesh = test::quad_grid_with_holes(40, 40, {505, 506, 545, 1010, 1011, 1212});
  for (Vec3& p : mesh.positions)
    p.z() = 0.3 * std::sin(0.3 * p.x()) * std::cos(0.15 * p.y()) + 0.002 * p.x() * p.y();
  return grid_disk(mesh);
}

ChartSolver direct_only() {
  ChartSolver s;
  s.iterative_from = 1 << 30;
  return s;
}

void expect_same_bits(const Chart& a, const Chart& b) {
  ASSERT_EQ(a.uv.size(), b.uv.size());
  for (size_t v = 0; v < a.uv.size(); ++v) {
    EXPECT_EQ(a.uv[v].x(), b.uv[v].x()) << "node " << v;
    EXPECT_EQ(a.uv[v].y(), b.uv[v].y()) << "node " << v;
  }
  EXPECT_EQ(a.triangles, b.triangles);
}

TEST(Chart, TheIterativeSolveGivesTheDirectSolvesChart) {
  const Disk d = bent_grid_disk();
  ASSERT_EQ(d.loops.size(), 4u);
  const Chart iterative = disk_chart(d.points, d.triangles, d.loops, d.outer);
  const Chart direct = disk_chart(d.points, d.triangles, d.loops, d.outer, direct_only());
  EXPECT_TRUE(iterative.iterative) << "the default solve of a system this large";
  EXPECT_FALSE(direct.iterative);
  EXPECT_FALSE(iterative.uniform_weights);
  ASSERT_EQ(iterative.uv.size(), direct.uv.size());
  double largest = 0;
  for (size_t v = 0; v < direct.uv.size(); ++v)
    largest = std::max(largest, (iterative.uv[v] - direct.uv[v]).norm());
  EXPECT_LT(largest, 1e-8) << "a residual of 1e-9 of the right-hand side";
  EXPECT_EQ(iterative.triangles, direct.triangles) << "the same winding of the fill triangles";
  for (Index t = 0; t < static_cast<Index>(iterative.triangles.size()); ++t)
    EXPECT_GT(signed_area(iterative, t), 0) << "triangle " << t;
}

TEST(Chart, AnIterativeSolutionThatLeavesAFlatTriangleGivesWayToTheDirectSolve) {
  const Disk d = bent_grid_disk();
  // A tolerance of 1 accepts the zero start: every free node at (0, 0), every triangle flat.
  ChartSolver inexact;
  inexact.iterative_from = 0;
  inexact.tolerance = 1;
  const Chart c = disk_chart(d.points, d.triangles, d.loops, d.outer, inexact);
  EXPECT_FALSE(c.iterative);
  EXPECT_FALSE(c.uniform_weights) << "the direct solve of the mean-value weights, not Tutte's";
  expect_same_bits(c, disk_chart(d.points, d.triangles, d.loops, d.outer, direct_only()));
}

TEST(Chart, AnUnconvergedIterativeSolveGivesWayToTheDirectSolve) {
  const Disk d = bent_grid_disk();
  ChartSolver none;
  none.iterative_from = 0;
  none.max_iterations = 0;
  const Chart c = disk_chart(d.points, d.triangles, d.loops, d.outer, none);
  EXPECT_FALSE(c.iterative);
  expect_same_bits(c, disk_chart(d.points, d.triangles, d.loops, d.outer, direct_only()));
}

TEST(Chart, ASmallSystemSolvedIterativelyIsInjective) {
  PolyMesh mesh = test::quad_grid_with_holes(8, 8, {27, 28, 35});
  for (Vec3& p : mesh.positions) p.z() = 0.3 * std::sin(p.x()) * std::cos(0.5 * p.y());
  const Disk d = grid_disk(mesh);
  ChartSolver always;
  always.iterative_from = 0;
  const Chart c = disk_chart(d.points, d.triangles, d.loops, d.outer, always);
  EXPECT_TRUE(c.iterative);
  const Chart direct = disk_chart(d.points, d.triangles, d.loops, d.outer);
  EXPECT_FALSE(direct.iterative) << "below the default size for the iterative solve";
  for (size_t v = 0; v < c.uv.size(); ++v) EXPECT_LT((c.uv[v] - direct.uv[v]).norm(), 1e-9);
  for (Index t = 0; t < static_cast<Index>(c.triangles.size()); ++t)
    EXPECT_GT(signed_area(c, t), 0) << "triangle " << t;
}

TEST(Chart, AZeroLengthOuterLoopIsRefused) {
  Disk d = grid_disk(test::quad_grid(3, 3));
  for (Vec3& p : d.points) p = Vec3::Zero();
  EXPECT_THROW(disk_chart(d.points, d.triangles, d.loops, d.outer), Error);
}

TEST(Chart, ACollapsedBindStillGivesAnInjectiveChart) {
  // Every interior vertex on one point: the mean-value weights degenerate; the chart stays
  // injective (uniform weights where it must).
  Disk d = grid_disk(test::quad_grid(4, 4));
  for (Index v = 0; v < static_cast<Index>(d.points.size()); ++v) {
    const int i = v % 5, j = v / 5;
    if (i > 0 && i < 4 && j > 0 && j < 4) d.points[v] = Vec3(2, 2, 0);
  }
  ChartSolver always;
  always.iterative_from = 0;
  for (const ChartSolver& solver : {ChartSolver{}, always}) {
    const Chart c = disk_chart(d.points, d.triangles, d.loops, d.outer, solver);
    for (Index t = 0; t < static_cast<Index>(c.triangles.size()); ++t)
      EXPECT_GT(signed_area(c, t), 0);
  }
}

}  // namespace
}  // namespace skinslide
