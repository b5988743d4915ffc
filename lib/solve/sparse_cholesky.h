// A sparse Cholesky factor computed once and then only read: many solves, from any thread.
// CHOLMOD (SuiteSparse) orders and factorises (simplicial: no BLAS, so the factor is the same on
// every machine); the factor is then regrouped into supernodes (runs of columns sharing their
// row pattern, stored as dense blocks) and solved by our own sweeps, so a solve needs no CHOLMOD
// workspace, no lock, and reads one row index per block row instead of one per entry.
#pragma once

#include <cstddef>
#include <vector>

#include "core/types.h"

namespace skinslide {

/// P A P^T = L L^T for a symmetric positive definite A. L is kept by supernodes: supernode k
/// holds columns [column_start[k], column_start[k+1]) over the rows
/// rows[row_start[k] .. row_start[k+1]) (its own columns first), as a dense block in column
/// order at value[value_start[k] ..] (the diagonal block's upper part zero). L's values are kept
/// in single precision: the factor serves as a preconditioner, where its error (about 1e-7
/// relative per entry) costs nothing, and a solve reads half the bytes.
struct CholeskyFactor {
  /// Row k of the factor is row `order[k]` of A.
  std::vector<Index> order;
  std::vector<Index> column_start;
  std::vector<Index> row_start;
  std::vector<Index> rows;
  std::vector<size_t> value_start;
  std::vector<float> value;
  Index size() const { return static_cast<Index>(order.size()); }
  /// Stored entries (with the diagonal blocks' zero upper parts).
  size_t entries() const { return value.size(); }
  /// Bytes held: what a patch's set-up keeps per factor.
  size_t bytes() const;
};

/// A symmetric matrix in compressed columns (or rows: the same arrays), both triangles or the
/// lower one stored, indices ascending in each column. Not owned.
struct SymmetricView {
  Index size = 0;
  const Index* start = nullptr;  ///< #size + 1
  const Index* index = nullptr;
  const double* value = nullptr;
};

/// Factorises A (its lower triangle is read) in CHOLMOD's nested-dissection order (METIS).
/// \throw Error(Numeric) when A is not positive definite.
CholeskyFactor cholesky_factor(const SymmetricView& A);

/// Solves (L L^T) x = b in place for the columns of `b` (#n by 2, one Vec2 a row), in double
/// precision with the stored factor: A x = b to single-precision accuracy. `work`: scratch of any
/// size, reused across calls.
void cholesky_solve(const CholeskyFactor& factor, Positions2& b, Positions2& work);

}  // namespace skinslide
