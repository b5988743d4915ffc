// The force-density bar net: assembly and solves (Schek 1974; Yang & Zhang 2010, section III.A,
// equation (1) with zero external forces: D x = -Df xf, D = C^T Q C over the free nodes).
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "core/types.h"
#include "solve/multigrid.h"

namespace skinslide {

/// The graph of a bar net: nodes 0..node_count-1, bars between them, and which nodes are fixed.
struct BarNet {
  Index node_count = 0;
  std::vector<std::array<Index, 2>> bars;
  std::vector<char> fixed;  ///< #nodes; 1 = fixed
};

/// Equilibrium of the net by a direct sparse solve (CHOLMOD LDL^T with its nested-dissection
/// ordering, x and y together).
/// \param q one force density per bar (> 0)
/// \param positions #nodes; the entries of fixed nodes are used, the others ignored
/// \param node_order if given, receives the free nodes in the factorisation's fill-reducing
///        order, for a FrameNetSolver on a net whose free nodes are among these
/// \return #nodes positions: fixed nodes as given, free nodes in equilibrium
/// \throw Error(Numeric) when the system is singular (a free node with no path to a fixed one)
///        or the result is not finite.
Positions2 solve_bar_net(const BarNet& net, const std::vector<double>& q,
                         const Positions2& positions, std::vector<Index>* node_order = nullptr);

/// The same equilibrium by CG preconditioned by an aggregation multigrid, from the free nodes'
/// given positions, to |r| <= tolerance |b| in x and in y: no ordering and no factor, so
/// memory and time grow as the net, where a factorisation grows as n^1.5. Past max_iterations
/// the net is solved directly.
/// \throw Error(Numeric) as solve_bar_net.
Positions2 solve_bar_net_multigrid(const BarNet& net, const std::vector<double>& q,
                                   const Positions2& positions, double tolerance,
                                   int max_iterations);

/// How FrameNetSolver solves a frame. Every method keeps the warm start when its residual
/// already meets cg_tolerance.
enum class FrameNetMethod {
  Cholesky,   ///< sparse Cholesky (CHOLMOD LDL^T), ordering and symbolic analysis done once
  Cg,         ///< Jacobi-preconditioned CG warm-started at the bind net, x and y separately
  Multigrid,  ///< CG preconditioned by an aggregation multigrid (solve/multigrid.h) built
              ///< once, warm-started at the bind net, x and y together
};

struct FrameNetOptions {
  double cg_tolerance = 1e-12;   ///< CG stops at |r| <= cg_tolerance * |b| (each of x and y)
  int cg_max_iterations = 2000;  ///< past it CG gives way to a direct solve
};

struct FrameNetSolution {
  Positions2 positions;  ///< #nodes
  int iterations = 0;    ///< CG iterations, the larger of x and y (0 for Cholesky and when the
                         ///< warm start is kept)
  double residual = 0;   ///< CG's final |r|/|b|, the larger of x and y (0 for Cholesky)
  bool direct = false;   ///< CG did not converge: solved by a fresh CHOLMOD factor instead
};

/// Solves the same net (same bars, same fixed nodes at the same positions) for many q vectors
/// (the paper's frame unwrap, section III.E). Built once: the free system's sparsity pattern, the
/// slot of each bar in it, and what the method needs: a fill-reducing ordering (CHOLMOD's nested
/// dissection) and the symbolic Cholesky factor, or the multigrid's levels. Per solve only
/// values change. `solve` is const and thread-safe: each call
/// owns its numeric factor, so frames can be solved in parallel with identical results.
class FrameNetSolver {
 public:
  /// \param positions #nodes: fixed nodes at their positions, free nodes at the warm start
  /// \param node_order for Cholesky, a fill-reducing order of (a superset of) the free nodes,
  ///        e.g. from solve_bar_net on the bind net; other nodes in it are skipped. Empty: a new
  ///        one.
  /// \throw Error(Numeric) when the symbolic analysis fails.
  FrameNetSolver(BarNet net, Positions2 positions, FrameNetMethod method,
                 const std::vector<Index>& node_order = {});
  /// This solver warm-started at other positions (the fixed nodes' entries included): the
  /// same system, slots, ordering and factor or levels, moved over instead of rebuilt. None of
  /// them depends on the positions, so a spare thread can build a solver while the positions it
  /// is to start from are still being solved.
  FrameNetSolver starting_at(Positions2 positions) &&;
  /// \param q one force density per bar (> 0)
  /// \return #nodes positions: fixed nodes as given, free nodes in equilibrium
  /// \throw Error(Numeric) when the system is singular or the result is not finite.
  FrameNetSolution solve(const std::vector<double>& q, const FrameNetOptions& options) const;
  const BarNet& net() const { return net_; }
  FrameNetMethod method() const { return method_; }
  Index free_node_count() const { return static_cast<Index>(free_nodes_.size()); }

 private:
  BarNet net_;
  FrameNetMethod method_;
  Positions2 start_;               // #nodes
  std::vector<Index> free_id_;     // node -> row of the free system, -1 if fixed
  std::vector<Index> free_nodes_;  // row -> node
  SparseMatrix pattern_;           // K_ff's pattern (values ignored)
  // Per bar: value slots (aa, bb, ab, ba) in pattern_, -1 if none (Cholesky, CG); for the
  // multigrid, the same slots in the order of its first level, which a frame's values are
  // summed into directly.
  std::vector<std::array<Index, 4>> slot_, level_slot_;
  struct Symbolic;
  std::shared_ptr<const Symbolic> symbolic_;               // K_ff's symbolic factor (Cholesky)
  std::shared_ptr<const AggregationMultigrid> multigrid_;  // its levels (multigrid)
};

}  // namespace skinslide
