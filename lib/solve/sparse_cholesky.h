// A sparse Cholesky factor computed once and then only read: many solves, from any thread.
// CHOLMOD (SuiteSparse) orders and factorises; the factor is then copied into plain arrays and
// solved by our own triangular sweeps, so a solve needs no CHOLMOD workspace, no BLAS and no
// lock, and gives the same bits on every thread.
#pragma once

#include <vector>

#include "core/types.h"

namespace skinslide {

/// P A P^T = L L^T for a symmetric positive definite A, L lower triangular in compressed
/// columns with each column's diagonal entry first. L's values are kept in single precision: the
/// factor serves as a preconditioner, where its error (about 1e-7 relative per entry) costs
/// nothing, and a solve reads half the bytes.
struct CholeskyFactor {
  /// Row k of the factor is row `order[k]` of A.
  std::vector<Index> order;
  std::vector<Index> column_start;  ///< #n + 1
  std::vector<Index> row;
  std::vector<float> value;
  Index size() const { return static_cast<Index>(order.size()); }
  /// Bytes held: what a patch's set-up keeps per factor.
  size_t bytes() const;
  Index nonzeros() const { return static_cast<Index>(value.size()); }
};

/// Factorises A (square, symmetric: its lower triangle is read) in CHOLMOD's nested-dissection
/// order (METIS), simplicial. \throw Error(Numeric) when A is not positive definite.
CholeskyFactor cholesky_factor(const SparseMatrix& A);

/// Solves (L L^T) x = b in place for the columns of `b` (#n by 2, one Vec2 a row), in double
/// precision with the stored factor: A x = b to single-precision accuracy.
/// `work`: scratch of any size, reused across calls.
void cholesky_solve(const CholeskyFactor& factor, Positions2& b, Positions2& work);

}  // namespace skinslide
