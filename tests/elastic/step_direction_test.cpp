// The elastic step's direction (lib/elastic/README.md rule 7): conjugate gradients on the chart
// system T^T (K x I3) T d = -T^T g, preconditioned by the bind's factor in tangent coordinates,
// reach the exact solution; truncated they still lower the step's model; held vertices do not
// move; the local re-solve around held vertices only lowers the model; crushed Jacobians give
// finite steps.
#include "elastic/step_direction.h"

#include <cmath>
#include <random>

#include <Eigen/SparseCholesky>
#include <gtest/gtest.h>

#include "elastic/relax.h"
#include "helpers/meshes.h"
#include "pipeline/bind_setup.h"

namespace skinslide {
namespace {

// A 40 x 40 grid with a hole: over 1 500 movable vertices.
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
  const ElasticMetric& K = e.metric;
  for (Index i = 0; i < K.size(); ++i)
    for (Index k = K.start[i]; k < K.start[i + 1]; ++k) {
      const Index j = K.column[k];
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
          double v = K.value[k] * T[i].col(a).dot(T[j].col(b));
          if (held[i] || held[j]) v = (i == j && a == b) ? 1.0 : 0.0;
          entries.emplace_back(2 * i + a, 2 * j + b, v);
        }
    }
  SparseMatrix H(2 * K.size(), 2 * K.size());
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

// The step's Gauss-Newton model at d: 1/2 d^T H d - r^T d (negative: the step lowers it).
double model(const SparseMatrix& H, const Eigen::VectorXd& r, const Eigen::VectorXd& d) {
  return 0.5 * d.dot(H * d) - r.dot(d);
}

TEST(StepDirection, ConvergesToTheChartSystemsSolution) {
  const auto e = grid_setup();
  ASSERT_GT(e->movable.size(), 1500u);
  const std::vector<Mat32> T = smooth_jacobians(*e);
  std::vector<char> held(e->movable.size(), 0);
  for (size_t i = 0; i < held.size(); i += 37) held[i] = 1;
  const std::vector<Vec3> g = random_gradient(T.size(), 7);
  DirectionWork work;
  const StepDirection dir =
      step_direction(e->metric, tangent_frames(T), g, held, work, DirectionSolve{1e-10, 200});
  ASSERT_TRUE(dir.finite);
  for (size_t i = 0; i < held.size(); ++i)
    if (held[i]) {
      EXPECT_EQ(dir.d[i], Vec2::Zero()) << "a held vertex does not move";
    }
  const SparseMatrix H = chart_system(*e, T, held);
  const Eigen::VectorXd r = chart_rhs(T, held, g);
  Eigen::SimplicialLDLT<SparseMatrix> exact(H);
  const Eigen::VectorXd x_exact = exact.solve(r);
  // Exact but for the 1e-12 (of the mean diagonal) whisper of the identity.
  EXPECT_LT((flat(dir.d) - x_exact).norm(), 1e-7 * x_exact.norm());
  EXPECT_LT(dir.iterations, 200) << "the bind's factor preconditions it";
}

TEST(StepDirection, TruncatedItStillLowersTheModel) {
  const auto e = grid_setup();
  const std::vector<Mat32> T = smooth_jacobians(*e);
  const std::vector<char> none(T.size(), 0);
  const std::vector<Vec3> g = random_gradient(T.size(), 3);
  const SparseMatrix H = chart_system(*e, T, none);
  const Eigen::VectorXd r = chart_rhs(T, none, g);
  DirectionWork work;
  double previous = 0;
  for (int iterations = 1; iterations <= 4; ++iterations) {
    const StepDirection dir =
        step_direction(e->metric, tangent_frames(T), g, {}, work, DirectionSolve{0, iterations});
    EXPECT_EQ(dir.iterations, iterations);
    const double q = model(H, r, flat(dir.d));
    EXPECT_LT(q, previous) << "each iteration lowers the model, from 0 at d = 0";
    previous = q;
  }
}

TEST(StepDirection, HeldDirectionOnlyLowersTheModel) {
  const auto e = grid_setup();
  const std::vector<Mat32> T = smooth_jacobians(*e);
  const std::vector<Vec3> g = random_gradient(T.size(), 13);
  DirectionWork work;
  const std::vector<TangentFrame> frames = tangent_frames(T);
  const StepDirection free = step_direction(e->metric, frames, g, {}, work);
  std::vector<char> held(T.size(), 0);
  for (size_t i = 100; i < T.size(); i += 211) held[i] = 1;
  // The free step with the held vertices' steps removed, against the held direction.
  Positions2 removed = free.d;
  for (size_t i = 0; i < held.size(); ++i)
    if (held[i]) removed[i].setZero();
  const StepDirection relaxed = held_direction(e->metric, frames, g, held, work);
  ASSERT_TRUE(relaxed.finite);
  const SparseMatrix H = chart_system(*e, T, held);
  const Eigen::VectorXd r = chart_rhs(T, held, g);
  EXPECT_LT(model(H, r, flat(relaxed.d)), model(H, r, flat(removed)));
  size_t changed_far = 0;
  for (size_t i = 0; i < held.size(); ++i) {
    if (held[i]) {
      EXPECT_EQ(relaxed.d[i], Vec2::Zero()) << "a held vertex does not move";
    } else if (relaxed.d[i] != removed[i]) {
      ++changed_far;
    }
  }
  EXPECT_GT(changed_far, 0u);
  EXPECT_LT(changed_far, T.size() / 2) << "only the rings around held vertices are relaxed";
}

TEST(StepDirection, CrushedJacobiansGiveFiniteSteps) {
  const auto e = grid_setup();
  std::vector<Mat32> T = smooth_jacobians(*e);
  // A band of the frame crushed to a line (rank one) and a spot crushed to a point (zero).
  for (size_t i = 0; i < T.size(); ++i) {
    const Vec2 uv = e->chart.uv[e->movable[i]];
    if (std::abs(uv.x() - 0.5) < 0.05) T[i].col(1) = 2.0 * T[i].col(0);
    if ((uv - Vec2(0.3, 0.3)).norm() < 0.05) T[i].setZero();
  }
  const std::vector<char> none(T.size(), 0);
  const std::vector<Vec3> g = random_gradient(T.size(), 11);
  DirectionWork work;
  const StepDirection dir = step_direction(e->metric, tangent_frames(T), g, none, work);
  ASSERT_TRUE(dir.finite);
  const Eigen::VectorXd r = chart_rhs(T, none, g);
  const Eigen::VectorXd x = flat(dir.d);
  ASSERT_TRUE(x.allFinite());
  // A descent direction: g . T d < 0, that is r . d > 0 for r = -T^T g.
  EXPECT_GT(r.dot(x), 0);
  for (size_t i = 0; i < T.size(); ++i) {
    if (T[i].isZero(0)) {
      EXPECT_LT(dir.d[i].norm(), 1e-6) << "a vertex crushed to a point stays";
    }
  }
}

TEST(SparseCholesky, SolvesToSinglePrecision) {
  const auto e = grid_setup();
  const ElasticMetric& K = e->metric;
  SparseMatrix A(K.size(), K.size());
  std::vector<Triplet> entries;
  for (Index i = 0; i < K.size(); ++i)
    for (Index k = K.start[i]; k < K.start[i + 1]; ++k)
      entries.emplace_back(i, K.column[k], K.value[k] + (i == K.column[k] ? K.shift : 0.0));
  A.setFromTriplets(entries.begin(), entries.end());
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  Positions2 b(K.size()), x, work;
  for (Vec2& v : b) v = Vec2(u(rng), u(rng));
  x = b;
  cholesky_solve(K.factor, x, work);
  Eigen::MatrixXd X(K.size(), 2), B(K.size(), 2);
  for (Index i = 0; i < K.size(); ++i) {
    X.row(i) = x[i].transpose();
    B.row(i) = b[i].transpose();
  }
  // The factor's values are floats: the residual is single precision's round-off times the
  // matrix's conditioning, far below what a preconditioner needs.
  const double residual = (A * X - B).norm() / B.norm();
  EXPECT_LT(residual, 1e-5) << residual;
  EXPECT_LT(K.factor.entries(), 60u * K.size()) << "nested dissection keeps the fill small";
}

}  // namespace
}  // namespace skinslide
