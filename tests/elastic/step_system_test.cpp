// The elastic step's linear system (lib/elastic/README.md rule 7): the multigrid in tangent
// coordinates solves the chart system T^T (K x I3) T d = -T^T g to its tolerance, held vertices
// do not move, and Jacobians crushed to a line or a point give finite steps.
#include "elastic/step_system.h"

#include <cmath>
#include <random>

#include <Eigen/SparseCholesky>
#include <gtest/gtest.h>

#include "elastic/relax.h"
#include "helpers/meshes.h"
#include "pipeline/bind_setup.h"

namespace skinslide {
namespace {

// A 40 x 40 grid with a hole: enough movable vertices (over 1 500) for a hierarchy of several
// levels, so that the multigrid, not its coarsest factorisation, does the solving.
std::shared_ptr<const ElasticSetup> grid_setup() {
  const PolyMesh mesh = test::quad_grid_with_holes(40, 40, {820, 821, 860, 861});
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{});
  return std::get<ElasticMethod>(setup.method).patches[0];
}

// Jacobians of a frame turned and sheared smoothly over the grid, as a skinned limb's are.
std::vector<Mat32> smooth_jacobians(const ElasticSetup& e) {
  std::vector<Mat32> T(e.movable.size());
  for (size_t i = 0; i < T.size(); ++i) {
    const Vec2 uv = e.chart.uv[e.movable[i]];
    const double a = 2.0 * uv.x(), s = 1.0 + 0.5 * uv.y();
    T[i] << std::cos(a) * s, 0.3, std::sin(a) * s, 0.0, 0.2 * uv.y(), 1.0 + uv.x();
  }
  return T;
}

std::vector<Vec3> random_gradient(size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3> g(n);
  for (Vec3& v : g) v = Vec3(u(rng), u(rng), u(rng));
  return g;
}

// The chart system itself, assembled from its definition, without tangent coordinates: held
// vertices' rows and columns the identity's.
SparseMatrix chart_system(const ElasticSetup& e, const std::vector<Mat32>& T,
                          const std::vector<char>& held) {
  std::vector<Triplet> entries;
  const Index m = static_cast<Index>(e.movable.size());
  for (Index i = 0; i < m; ++i)
    for (Index k = e.metric_start[i]; k < e.metric_start[i + 1]; ++k) {
      const Index j = e.metric_column[k];
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
          double v = e.metric_value[k] * T[i].col(a).dot(T[j].col(b));
          if (held[i] || held[j]) v = (i == j && a == b) ? 1.0 : 0.0;
          entries.emplace_back(2 * i + a, 2 * j + b, v);
        }
    }
  SparseMatrix H(2 * m, 2 * m);
  H.setFromTriplets(entries.begin(), entries.end());
  return H;
}

Eigen::VectorXd chart_rhs(const std::vector<Mat32>& T, const std::vector<char>& held,
                          const std::vector<Vec3>& g) {
  Eigen::VectorXd r = Eigen::VectorXd::Zero(2 * static_cast<Index>(T.size()));
  for (size_t i = 0; i < T.size(); ++i)
    if (!held[i]) r.segment<2>(2 * static_cast<Index>(i)) = -(T[i].transpose() * g[i]);
  return r;
}

Eigen::VectorXd flat(const Positions2& d) {
  Eigen::VectorXd x(2 * static_cast<Index>(d.size()));
  for (size_t i = 0; i < d.size(); ++i) x.segment<2>(2 * static_cast<Index>(i)) = d[i];
  return x;
}

TEST(StepSystem, HierarchyHasSeveralLevels) {
  const auto e = grid_setup();
  ASSERT_TRUE(e && e->step_multigrid);
  EXPECT_GT(e->movable.size(), 1500u);
  EXPECT_GE(e->step_multigrid->hierarchy.levels(), 3);
}

TEST(StepSystem, SolvesTheChartSystemToItsTolerance) {
  const auto e = grid_setup();
  const std::vector<Mat32> T = smooth_jacobians(*e);
  std::vector<char> held(e->movable.size(), 0);
  for (size_t i = 0; i < held.size(); i += 37) held[i] = 1;
  const std::vector<Vec3> g = random_gradient(T.size(), 7);
  StepSystem system(e->metric_start, e->metric_column, e->metric_value, *e->step_multigrid);
  Positions2 d;
  ASSERT_TRUE(system.solve(T, held, g, d));
  EXPECT_EQ(system.direct_solves, 0) << "a smooth frame is the multigrid's";
  EXPECT_GT(system.multigrid_iterations, 0);
  EXPECT_LT(system.multigrid_iterations, 60);
  const SparseMatrix H = chart_system(*e, T, held);
  const Eigen::VectorXd r = chart_rhs(T, held, g);
  const Eigen::VectorXd x = flat(d);
  for (size_t i = 0; i < held.size(); ++i) {
    if (held[i]) {
      EXPECT_EQ(d[i], Vec2::Zero()) << "a held vertex does not move";
    }
  }
  // The tangent system's residual is 1e-4 of its right-hand side; in the chart's coordinates
  // that is within the tangent frames' conditioning (here under 10).
  EXPECT_LT((H * x - r).norm(), 1e-3 * r.norm());
  Eigen::SimplicialLDLT<SparseMatrix> exact(H);
  const Eigen::VectorXd x_exact = exact.solve(r);
  EXPECT_LT((x - x_exact).norm(), 1e-2 * x_exact.norm());
}

TEST(StepSystem, SmallPatchesAreSolvedExactly) {
  const PolyMesh mesh = test::quad_grid_with_holes(6, 6, {});
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{});
  const ElasticSetup& e = *std::get<ElasticMethod>(setup.method).patches[0];
  ASSERT_EQ(e.step_multigrid->hierarchy.levels(), 1)
      << "25 movable vertices: the coarsest level only";
  const std::vector<Mat32> T = smooth_jacobians(e);
  std::vector<char> held(e.movable.size(), 0);
  held[3] = 1;
  const std::vector<Vec3> g = random_gradient(T.size(), 5);
  StepSystem system(e.metric_start, e.metric_column, e.metric_value, *e.step_multigrid);
  Positions2 d;
  ASSERT_TRUE(system.solve(T, held, g, d));
  EXPECT_EQ(system.direct_solves, 1);
  EXPECT_EQ(system.multigrid_iterations, 0);
  const Eigen::VectorXd r = chart_rhs(T, held, g);
  // Exact but for the 1e-12 (of the mean diagonal) whisper of the identity.
  EXPECT_LT((chart_system(e, T, held) * flat(d) - r).norm(), 1e-10 * r.norm());
  EXPECT_EQ(d[3], Vec2::Zero());
}

TEST(StepSystem, CrushedJacobiansGiveFiniteSteps) {
  const auto e = grid_setup();
  std::vector<Mat32> T = smooth_jacobians(*e);
  // A band of the frame crushed to a line (rank one) and a spot crushed to a point (zero).
  for (size_t i = 0; i < T.size(); ++i) {
    const Vec2 uv = e->chart.uv[e->movable[i]];
    if (std::abs(uv.x() - 0.5) < 0.05) T[i].col(1) = 2.0 * T[i].col(0);
    if ((uv - Vec2(0.3, 0.3)).norm() < 0.05) T[i].setZero();
  }
  const std::vector<char> held(T.size(), 0);
  const std::vector<Vec3> g = random_gradient(T.size(), 11);
  StepSystem system(e->metric_start, e->metric_column, e->metric_value, *e->step_multigrid);
  Positions2 d;
  ASSERT_TRUE(system.solve(T, held, g, d));
  const Eigen::VectorXd r = chart_rhs(T, held, g);
  const Eigen::VectorXd x = flat(d);
  ASSERT_TRUE(x.allFinite());
  // A descent direction: g . T d < 0, that is r . d > 0 for r = -T^T g.
  EXPECT_GT(r.dot(x), 0);
  for (size_t i = 0; i < T.size(); ++i) {
    if (T[i].isZero(0)) {
      EXPECT_LT(d[i].norm(), 1e-6) << "a vertex crushed to a point stays";
    }
  }
}

}  // namespace
}  // namespace skinslide
