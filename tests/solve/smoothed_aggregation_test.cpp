// The chart's iterative solver: BiCGSTAB with a smoothed-aggregation V-cycle on nonsymmetric
// M-matrices, against a sparse LU solve of the same systems.
#include "solve/smoothed_aggregation.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include <Eigen/SparseLU>

namespace skinslide {
namespace {

using Mat2 = Eigen::Matrix<double, Eigen::Dynamic, 2>;

// An n x n grid's interior rows of a row-normalised random-weight Laplacian (every row's weights
// to its four neighbours sum to 1, a border neighbour's share moved to the right-hand side): a
// nonsymmetric M-matrix like the chart's.
struct GridSystem {
  RowMatrix A;
  Mat2 b;
};

GridSystem grid_system(int n, unsigned seed) {
  std::mt19937 rng{seed};
  std::uniform_real_distribution<double> uw(0.05, 1.0), ub(0.0, 1.0);
  const int m = n - 2;  // interior rows per side
  auto id = [m](int i, int j) { return (i - 1) * m + (j - 1); };
  GridSystem s;
  s.A.rows = m * m;
  s.A.start.assign(1, 0);
  s.b = Mat2::Zero(m * m, 2);
  for (int i = 1; i <= m; ++i)
    for (int j = 1; j <= m; ++j) {
      const int neighbours[4][2] = {{i - 1, j}, {i, j - 1}, {i, j + 1}, {i + 1, j}};
      double w[4], sum = 0;
      for (double& x : w) sum += (x = uw(rng));
      bool diagonal_placed = false;
      for (int q = 0; q < 4; ++q) {
        const auto [a, c] = neighbours[q];
        const double weight = w[q] / sum;
        const bool border = a == 0 || c == 0 || a == n - 1 || c == n - 1;
        if (border) {
          s.b.row(id(i, j)) += weight * Eigen::RowVector2d(ub(rng), ub(rng));
          continue;
        }
        if (!diagonal_placed && id(a, c) > id(i, j)) {
          s.A.column.push_back(id(i, j));
          s.A.value.push_back(1.0);
          diagonal_placed = true;
        }
        s.A.column.push_back(id(a, c));
        s.A.value.push_back(-weight);
      }
      if (!diagonal_placed) {
        s.A.column.push_back(id(i, j));
        s.A.value.push_back(1.0);
      }
      s.A.start.push_back(static_cast<Index>(s.A.column.size()));
    }
  return s;
}

Mat2 direct(const GridSystem& s) {
  const Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor, Index>> rows(
      s.A.rows, s.A.rows, static_cast<Index>(s.A.column.size()), s.A.start.data(),
      s.A.column.data(), s.A.value.data());
  SparseMatrix A = rows;
  Eigen::SparseLU<SparseMatrix> lu(A);
  return lu.solve(s.b);
}

double relative_residual(const GridSystem& s, const Mat2& x) {
  const Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor, Index>> A(
      s.A.rows, s.A.rows, static_cast<Index>(s.A.column.size()), s.A.start.data(),
      s.A.column.data(), s.A.value.data());
  const Mat2 r = s.b - A * x;
  return std::max(r.col(0).norm() / s.b.col(0).norm(), r.col(1).norm() / s.b.col(1).norm());
}

TEST(SmoothedAggregation, SolvesANonsymmetricMMatrixToTheTolerance) {
  const GridSystem s = grid_system(120, 1);  // 13 924 rows: several levels
  Mat2 x = Mat2::Zero(s.A.rows, 2);
  const IterativeSolve r = solve_smoothed_aggregation(s.A, s.b, x, 1e-10, 100);
  ASSERT_TRUE(r.converged);
  EXPECT_GT(r.levels, 2);
  EXPECT_LE(r.iterations, 30);
  EXPECT_LE(r.residual, 1e-10);
  EXPECT_LE(relative_residual(s, x), 1e-10) << "the true residual, not the recurrence's";
  EXPECT_LT((x - direct(s)).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(SmoothedAggregation, StartsFromTheGivenSolution) {
  const GridSystem s = grid_system(40, 2);
  Mat2 x = direct(s);
  const IterativeSolve r = solve_smoothed_aggregation(s.A, s.b, x, 1e-6, 100);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.iterations, 0) << "an exact start is already converged";
}

TEST(SmoothedAggregation, SameBitsEveryRun) {
  const GridSystem s = grid_system(60, 3);
  Mat2 x1 = Mat2::Zero(s.A.rows, 2), x2 = Mat2::Zero(s.A.rows, 2);
  solve_smoothed_aggregation(s.A, s.b, x1, 1e-9, 100);
  solve_smoothed_aggregation(s.A, s.b, x2, 1e-9, 100);
  EXPECT_EQ(std::memcmp(x1.data(), x2.data(), sizeof(double) * x1.size()), 0);
}

TEST(SmoothedAggregation, ASmallSystemIsFactorisedOutright) {
  const GridSystem s = grid_system(8, 4);  // 36 rows: no coarser level
  Mat2 x = Mat2::Zero(s.A.rows, 2);
  const IterativeSolve r = solve_smoothed_aggregation(s.A, s.b, x, 1e-12, 100);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.levels, 1);
  EXPECT_LE(r.iterations, 2);
}

TEST(SmoothedAggregation, ReportsWhatItCannotSolve) {
  const GridSystem s = grid_system(50, 5);
  {
    Mat2 x = Mat2::Zero(s.A.rows, 2);
    const IterativeSolve r = solve_smoothed_aggregation(s.A, s.b, x, 1e-12, 1);
    EXPECT_FALSE(r.converged) << "one iteration is not enough";
    EXPECT_EQ(r.iterations, 1);
    EXPECT_GT(r.residual, 1e-12);
    EXPECT_TRUE(x.allFinite());
  }
  {
    GridSystem bad = s;
    for (Index k = bad.A.start[7]; k < bad.A.start[8]; ++k)
      if (bad.A.column[k] == 7) bad.A.value[k] = -1;  // a row without a positive diagonal
    Mat2 x = Mat2::Zero(s.A.rows, 2);
    EXPECT_FALSE(solve_smoothed_aggregation(bad.A, bad.b, x, 1e-9, 100).converged);
  }
  {
    RowMatrix empty;
    Mat2 x(0, 2), b(0, 2);
    EXPECT_TRUE(solve_smoothed_aggregation(empty, b, x, 1e-9, 100).converged);
  }
}

}  // namespace
}  // namespace skinslide
