// The linear system of one elastic Gauss-Newton step (README rule 7): per movable vertex a chart
// step d_i, with the frame's Jacobian T_i (3x2) turning it into 3D motion, against the bind's
// ARAP metric K. It is solved in each vertex's tangent coordinates, where it is close to K x I2
// whatever the chart's distortion, by the aggregation multigrid built once per patch from K.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/SparseCholesky>

#include "core/types.h"
#include "solve/multigrid.h"

namespace skinslide {

using Mat32 = Eigen::Matrix<double, 3, 2>;

/// The step system's sparsity over 2m unknowns (x and y of each movable vertex's chart step):
/// the 2x2 blocks of the metric's (compressed rows `start`, `column`), compressed columns, rows
/// ascending, all values zero.
SparseMatrix step_pattern(const std::vector<Index>& start, const std::vector<Index>& column);

/// The multigrid for every step system of a patch, built at bind time from K's nearest M-matrix
/// (each positive off-diagonal entry, from an obtuse bind angle, moved onto the diagonals it
/// couples) times I2: the aggregates pair x with x and y with y.
struct StepMultigrid {
  AggregationMultigrid hierarchy;
  /// Per nonzero of step_pattern, in its order: the level-0 nonzero that holds it, so that a
  /// frame assembles its system straight into the multigrid's order.
  std::vector<Index> level0_slot;
};

std::shared_ptr<const StepMultigrid> step_multigrid(const std::vector<Index>& start,
                                                    const std::vector<Index>& column,
                                                    const std::vector<double>& value);

/// One frame's step systems: (T^T (K x I3) T + mu I) d = -T^T g over the movable vertices, held
/// vertices' rows and columns the identity's. Holds its work arrays; one per frame and thread.
class StepSystem {
 public:
  /// `start`, `column`, `value`: K over the movable vertices, compressed rows (both triangles);
  /// `multigrid`: step_multigrid of the same K. All must outlive the StepSystem.
  StepSystem(const std::vector<Index>& start, const std::vector<Index>& column,
             const std::vector<double>& value, const StepMultigrid& multigrid);

  /// Solves for d (per movable vertex; zero where held) given each vertex's Jacobian T, held
  /// flags and the energy's 3D gradient g per movable vertex. False when no solve succeeds.
  bool solve(const std::vector<Mat32>& T, const std::vector<char>& held,
             const std::vector<Vec3>& gradient, Positions2& d);

  int multigrid_iterations = 0;  ///< over all solves so far
  int direct_solves = 0;  ///< solves by sparse factorisation: small systems, multigrid stalls

 private:
  bool solve_directly(const Eigen::Matrix<double, Eigen::Dynamic, 2>& b,
                      Eigen::Matrix<double, Eigen::Dynamic, 2>& x);
  double& entry(Index nonzero) { return values_[multigrid_.level0_slot[nonzero]]; }

  const std::vector<Index>& start_;
  const std::vector<Index>& column_;
  const std::vector<double>& value_;
  const StepMultigrid& multigrid_;
  std::vector<double> values_;  // the tangent-coordinate system, in the multigrid's level-0 order
  SparseMatrix H_;              // the same for a direct solve, step_pattern's (built on demand)
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> direct_;
};

}  // namespace skinslide
