#include "solve/multigrid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <thread>

#include <Eigen/SparseCholesky>

namespace skinslide {
namespace {

using Mat2 = Eigen::Matrix<double, Eigen::Dynamic, 2>;

// The free system of an n x n grid of bars whose border ring is fixed: a weighted graph
// Laplacian restricted to the interior, both triangles stored. Weights from `weight`.
template <class Weight>
SparseMatrix grid_system(int n, Weight weight) {
  auto id = [n](int i, int j) { return i * n + j; };
  std::vector<Triplet> t;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int neighbours[4][2] = {{i + 1, j}, {i - 1, j}, {i, j + 1}, {i, j - 1}};
      for (const auto& [a, b] : neighbours) {
        const bool inside = a >= 0 && a < n && b >= 0 && b < n;
        if (inside && id(a, b) < id(i, j)) continue;  // each interior bar once
        const double q = weight();
        t.emplace_back(id(i, j), id(i, j), q);
        if (inside) {
          t.emplace_back(id(a, b), id(a, b), q);
          t.emplace_back(id(i, j), id(a, b), -q);
          t.emplace_back(id(a, b), id(i, j), -q);
        }
      }
    }
  SparseMatrix A(n * n, n * n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

SparseMatrix unit_grid(int n) {
  return grid_system(n, [] { return 1.0; });
}

SparseMatrix random_grid(int n, unsigned seed) {
  std::mt19937 rng{seed};
  std::uniform_real_distribution<double> uq(1e-3, 1.0);
  return grid_system(n, [&] { return uq(rng); });
}

Mat2 random_rhs(Eigen::Index rows, unsigned seed) {
  std::mt19937 rng{seed};
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mat2 b(rows, 2);
  for (Eigen::Index i = 0; i < rows; ++i) b.row(i) << u(rng), u(rng);
  return b;
}

TEST(AggregationMultigrid, EachLevelSumsAggregatesOfTheOneAbove) {
  const SparseMatrix A = unit_grid(60);
  const AggregationMultigrid mg(A);
  ASSERT_GE(mg.levels(), 3);
  EXPECT_EQ(mg.level(0).rows, 3600);
  for (int l = 0; l + 1 < mg.levels(); ++l) {
    const auto& fine = mg.level(l);
    const auto& coarse = mg.level(l + 1);
    EXPECT_LE(coarse.rows * 3, fine.rows * 2) << "level " << l;  // at least 1.5x coarser
    std::vector<int> size(coarse.rows, 0);
    for (Index i = 0; i < fine.rows; ++i) ++size[fine.aggregate[i]];
    for (int s : size) {
      EXPECT_GE(s, 1);
      EXPECT_LE(s, 4);  // two pairings
    }
    // Fine nonzero (i, j) lands in coarse row aggregate[i], column aggregate[j].
    for (Index i = 0; i < fine.rows; ++i)
      for (Index k = fine.start[i]; k < fine.start[i + 1]; ++k) {
        const Index slot = fine.coarse_slot[k];
        const Index ci = fine.aggregate[i];
        ASSERT_GE(slot, coarse.start[ci]);
        ASSERT_LT(slot, coarse.start[ci + 1]);
        EXPECT_EQ(coarse.column[slot], fine.aggregate[fine.column[k]]);
      }
    for (Index c = 0; c < coarse.rows; ++c) EXPECT_EQ(coarse.column[coarse.diagonal[c]], c);
  }
  EXPECT_LE(mg.level(mg.levels() - 1).rows, 200);
}

// A's rows and columns renumbered: row i of A is row new_id[i] of the result.
SparseMatrix renumbered(const SparseMatrix& A, const std::vector<Index>& new_id) {
  std::vector<Triplet> t;
  for (Index c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it)
      t.emplace_back(new_id[it.row()], new_id[it.col()], it.value());
  SparseMatrix B(A.rows(), A.cols());
  B.setFromTriplets(t.begin(), t.end());
  B.makeCompressed();
  return B;
}

// Level 0's bandwidth: how far apart in the sweep two coupled rows can be.
Index sweep_bandwidth(const AggregationMultigrid& mg) {
  const auto& top = mg.level(0);
  Index width = 0;
  for (Index i = 0; i < top.rows; ++i)
    for (Index k = top.start[i]; k < top.start[i + 1]; ++k)
      width = std::max(width, std::abs(top.column[k] - i));
  return width;
}

TEST(AggregationMultigrid, SweepsCrossTheNetAsAFrontWhateverTheNodeOrder) {
  const int n = 60;
  const SparseMatrix A = random_grid(n, 11);
  std::vector<Index> shuffle(A.rows());
  for (Index i = 0; i < A.rows(); ++i) shuffle[i] = i;
  std::shuffle(shuffle.begin(), shuffle.end(), std::mt19937{12});
  const SparseMatrix B = renumbered(A, shuffle);
  const AggregationMultigrid grid_order(A), shuffled(B);
  // Breadth first from a corner, a front of an n x n grid holds at most n + 1 rows, and coupled
  // rows are at most two fronts apart; the shuffled numbering alone has coupled rows thousands
  // of rows apart.
  EXPECT_LE(sweep_bandwidth(grid_order), 2 * (n + 1));
  EXPECT_LE(sweep_bandwidth(shuffled), 2 * (n + 1));
  // And the solve does not depend on the numbering beyond a tie or two.
  const Mat2 b = random_rhs(A.rows(), 13);
  Mat2 b_shuffled(b.rows(), 2), x = Mat2::Zero(b.rows(), 2), y = Mat2::Zero(b.rows(), 2);
  for (Index i = 0; i < A.rows(); ++i) b_shuffled.row(shuffle[i]) = b.row(i);
  const MultigridResult ra = grid_order.solve(A, b, x, 1e-12, 200);
  const MultigridResult rb = shuffled.solve(B, b_shuffled, y, 1e-12, 200);
  ASSERT_TRUE(ra.converged && rb.converged);
  EXPECT_LE(std::abs(ra.iterations - rb.iterations), 2);
  for (Index i = 0; i < A.rows(); ++i)
    EXPECT_LT((x.row(i) - y.row(shuffle[i])).norm(), 1e-9 * x.norm() / std::sqrt(A.rows()));
}

TEST(AggregationMultigrid, SolvesOtherWeightsOnTheSamePatternToTheTolerance) {
  const AggregationMultigrid mg(unit_grid(70));  // built from unit weights
  for (unsigned seed = 0; seed < 3; ++seed) {
    const SparseMatrix A = random_grid(70, seed);  // solved with random ones
    const Mat2 b = random_rhs(A.rows(), seed + 10);
    Mat2 x = Mat2::Zero(A.rows(), 2);
    const MultigridResult r = mg.solve(A, b, x, 1e-12, 200);
    ASSERT_TRUE(r.converged);
    EXPECT_GT(r.iterations, 0);
    EXPECT_LE(r.residual, 1e-12);
    const Mat2 residual = b - A * x;  // the true residual, not CG's recurrence
    for (int c = 0; c < 2; ++c) EXPECT_LE(residual.col(c).norm(), 2e-12 * b.col(c).norm());
    const Eigen::SimplicialLDLT<SparseMatrix> ldlt(A);
    const Mat2 exact = ldlt.solve(b);
    EXPECT_LT((x - exact).norm(), 1e-8 * exact.norm());
  }
}

TEST(AggregationMultigrid, AWarmStartNeedsFewerIterations) {
  const SparseMatrix A = random_grid(50, 3);
  const AggregationMultigrid mg(A);
  const Mat2 b = random_rhs(A.rows(), 4);
  Mat2 cold = Mat2::Zero(A.rows(), 2);
  const MultigridResult from_zero = mg.solve(A, b, cold, 1e-12, 200);
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(A);
  Mat2 warm = ldlt.solve(b) + 1e-6 * random_rhs(A.rows(), 5);
  const MultigridResult from_near = mg.solve(A, b, warm, 1e-12, 200);
  ASSERT_TRUE(from_zero.converged && from_near.converged);
  EXPECT_LT(from_near.iterations, from_zero.iterations);
}

TEST(AggregationMultigrid, SameBitsEveryRunAndFromConcurrentThreads) {
  const SparseMatrix A = random_grid(64, 7);
  const AggregationMultigrid mg(unit_grid(64));
  const Mat2 b = random_rhs(A.rows(), 8);
  Mat2 first = Mat2::Zero(A.rows(), 2);
  mg.solve(A, b, first, 1e-12, 200);
  Mat2 in_thread[2] = {Mat2::Zero(A.rows(), 2), Mat2::Zero(A.rows(), 2)};
  std::thread t0([&] { mg.solve(A, b, in_thread[0], 1e-12, 200); });
  std::thread t1([&] { mg.solve(A, b, in_thread[1], 1e-12, 200); });
  t0.join();
  t1.join();
  for (const Mat2& x : in_thread)
    EXPECT_EQ(0, std::memcmp(x.data(), first.data(), sizeof(double) * first.size()));
}

TEST(AggregationMultigrid, StopsUnconvergedAtTheIterationLimit) {
  const SparseMatrix A = random_grid(40, 9);
  const AggregationMultigrid mg(A);
  const Mat2 b = random_rhs(A.rows(), 10);
  Mat2 x = Mat2::Zero(A.rows(), 2);
  const MultigridResult r = mg.solve(A, b, x, 1e-14, 2);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.iterations, 2);
  EXPECT_GT(r.residual, 1e-14);
  EXPECT_TRUE(x.allFinite());
}

// Densities that jump by up to 12 orders of magnitude between neighbours: pairing stalls and the
// K-cycle barely helps. The solve gives up early (for a direct solve) instead of running on.
TEST(AggregationMultigrid, GivesUpEarlyWhenDensitiesJumpByManyOrdersOfMagnitude) {
  std::mt19937 rng{13};
  std::uniform_real_distribution<double> exponent(-12.0, 0.0);
  const SparseMatrix A = grid_system(60, [&] { return std::pow(10.0, exponent(rng)); });
  const AggregationMultigrid mg(A);
  const Mat2 b = random_rhs(A.rows(), 14);
  Mat2 x = Mat2::Zero(A.rows(), 2);
  const MultigridResult r = mg.solve(A, b, x, 1e-12, 2000);
  EXPECT_FALSE(r.converged);
  EXPECT_LT(r.iterations, 100);
  EXPECT_TRUE(x.allFinite());
}

// Rows with no coupling at all cannot be paired: the first level is the coarsest, however large,
// and its sparse factor solves it at once.
TEST(AggregationMultigrid, AnUncoupledSystemOfAnySizeIsSolvedOnItsOwnLevel) {
  const Index n = 50000;
  SparseMatrix A(n, n);
  std::vector<Triplet> diagonal;
  for (Index i = 0; i < n; ++i) diagonal.emplace_back(i, i, 1.0 + i % 7);
  A.setFromTriplets(diagonal.begin(), diagonal.end());
  A.makeCompressed();
  const AggregationMultigrid mg(A);
  EXPECT_EQ(mg.levels(), 1);
  const Mat2 b = random_rhs(n, 15);
  Mat2 x = Mat2::Zero(n, 2);
  const MultigridResult r = mg.solve(A, b, x, 1e-12, 10);
  EXPECT_TRUE(r.converged);
  for (Index i = 0; i < n; i += 997) EXPECT_NEAR(x(i, 0), b(i, 0) / (1.0 + i % 7), 1e-14);
}

TEST(AggregationMultigrid, ASmallSystemIsItsOwnCoarsestLevel) {
  const SparseMatrix A = random_grid(10, 11);  // 100 rows: solved densely
  const AggregationMultigrid mg(A);
  EXPECT_EQ(mg.levels(), 1);
  const Mat2 b = random_rhs(A.rows(), 12);
  Mat2 x = Mat2::Zero(A.rows(), 2);
  const MultigridResult r = mg.solve(A, b, x, 1e-12, 5);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.iterations, 2);
}

}  // namespace
}  // namespace skinslide
