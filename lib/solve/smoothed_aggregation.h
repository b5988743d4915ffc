// An iterative solver for the elastic chart's embedding systems: sparse nonsymmetric M-matrices
// (positive diagonal, non-positive off-diagonal entries, rows diagonally dominant), two
// right-hand sides at once. BiCGSTAB (van der Vorst 1992), right-preconditioned by one V-cycle of
// smoothed-aggregation multigrid (Vanek, Mandel & Brezina 1996): each level's rows grouped into
// aggregates (a row and its strong neighbours), the piecewise-constant prolongator smoothed by one
// damped Jacobi step, the next level's matrix P^T A P; a forward Gauss-Seidel sweep before the
// coarse correction and a backward one after it; the coarsest level factorised (sparse LU).
#pragma once

#include <vector>

#include "core/types.h"

namespace skinslide {

/// A square sparse matrix in compressed rows: each row's columns ascending, its diagonal among
/// them.
struct RowMatrix {
  Index rows = 0;
  std::vector<Index> start{0};  ///< #rows + 1: row i is [start[i], start[i + 1])
  std::vector<Index> column;
  std::vector<double> value;
};

struct IterativeSolve {
  int iterations = 0;   ///< BiCGSTAB iterations (two V-cycles each)
  double residual = 0;  ///< final |b - A x| / |b|, the larger of the two columns
  bool converged = false;
  int levels = 0;  ///< of the multigrid hierarchy (1: the matrix was factorised directly)
};

/// Solves A x = b for the two columns of b, starting from x. Converged when the true residual
/// |b - A x| <= tolerance |b| in each column; unconverged after max_iterations, on a breakdown
/// (a vanishing BiCGSTAB coefficient), when the hierarchy cannot be built (a coarse level without
/// a positive diagonal, aggregates that stop shrinking the matrix) or on a non-finite value: a
/// caller then solves directly. Deterministic: one thread, a fixed order of operations.
IterativeSolve solve_smoothed_aggregation(const RowMatrix& A,
                                          const Eigen::Matrix<double, Eigen::Dynamic, 2>& b,
                                          Eigen::Matrix<double, Eigen::Dynamic, 2>& x,
                                          double tolerance, int max_iterations);

}  // namespace skinslide
