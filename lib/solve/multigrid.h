// An aggregation multigrid for the per-frame systems of both methods (the paper's frame nets,
// the elastic method's steps): conjugate gradients preconditioned by a K-cycle over pairwise
// aggregates (Notay 2010, "An aggregation-based algebraic multigrid method"; Notay & Vassilevski
// 2008, "Recursive Krylov-based multigrid cycles"). The aggregates and every level's sparsity
// pattern are built once from one matrix; a solve only sums a new matrix's values into the coarse
// levels, so frames whose systems differ share one hierarchy.
#pragma once

#include <vector>

#include "core/types.h"

namespace skinslide {

struct MultigridResult {
  int iterations = 0;   ///< outer CG iterations, the larger of the two columns
  double residual = 0;  ///< final |r|/|b|, the larger of the two columns
  bool converged = false;
};

class AggregationMultigrid {
 public:
  /// \param A symmetric, both triangles stored, positive definite with non-positive off-diagonal
  ///        entries (a bar net's free system); its values pick the aggregates
  explicit AggregationMultigrid(const SparseMatrix& A);

  /// Solves A x = b for two right-hand sides at once (x and y of a net), starting from x.
  /// A has the pattern the hierarchy was built from; its values may differ.
  /// Stops when |r| <= tolerance |b| in each column (converged), or unconverged after
  /// max_iterations or when 20 iterations in a row cut the residual less than 10x (stagnation,
  /// for a caller to solve directly instead).
  /// Deterministic, const and thread-safe: all per-solve values live in the call.
  MultigridResult solve(const SparseMatrix& A, const Eigen::Matrix<double, Eigen::Dynamic, 2>& b,
                        Eigen::Matrix<double, Eigen::Dynamic, 2>& x, double tolerance,
                        int max_iterations) const;

  /// The same, with A given by its values in the order of level 0's nonzeros (value_slot): a
  /// caller that assembles A there needs neither A's compressed copy nor the gather from it.
  MultigridResult solve(const std::vector<double>& level0_values,
                        const Eigen::Matrix<double, Eigen::Dynamic, 2>& b,
                        Eigen::Matrix<double, Eigen::Dynamic, 2>& x, double tolerance,
                        int max_iterations) const;

  /// Level 0's nonzero k holds the nonzero value_slot()[k] of the matrix the hierarchy was
  /// built from (in its compressed storage); one to one.
  const std::vector<Index>& value_slot() const { return value_slot_; }

  /// Per level: rows and sparsity pattern (compressed rows, columns sorted, the diagonal's
  /// position), and for all but the coarsest the row of the next level each row is summed into
  /// and where each nonzero lands in the next level's values. Level 0 is the matrix with its
  /// rows and columns permuted into the order its sweeps take.
  struct Level {
    Index rows = 0;
    std::vector<Index> start, column, diagonal;
    std::vector<Index> aggregate;    ///< #rows: row of the next level
    std::vector<Index> coarse_slot;  ///< #nonzeros: nonzero of the next level
  };
  int levels() const { return static_cast<int>(levels_.size()); }
  const Level& level(int l) const { return levels_[l]; }

 private:
  std::vector<Level> levels_;      // level 0: the matrix's rows in sweep order
  std::vector<Index> order_;       // row of level 0 -> row of the matrix
  std::vector<Index> value_slot_;  // nonzero of level 0 -> nonzero of the matrix
};

}  // namespace skinslide
