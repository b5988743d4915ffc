#include "paper/bar_net.h"

#include <algorithm>
#include <cmath>

#include <Eigen/IterativeLinearSolvers>

#include "core/check.h"
#include "core/error.h"
#include "solve/cholmod.h"

namespace skinslide {
namespace {

using Mat2 = Eigen::Matrix<double, Eigen::Dynamic, 2>;

struct FreeSystem {
  std::vector<Index> free_id;
  std::vector<Index> free_nodes;
};

FreeSystem free_system(const BarNet& net) {
  FreeSystem s;
  s.free_id.assign(net.node_count, -1);
  for (Index v = 0; v < net.node_count; ++v)
    if (!net.fixed[v]) {
      s.free_id[v] = static_cast<Index>(s.free_nodes.size());
      s.free_nodes.push_back(v);
    }
  return s;
}

// Right-hand side -K_fc x_c: each bar from a free node a to a fixed node b pulls a towards b.
Mat2 fixed_pull(const BarNet& net, const std::vector<Index>& free_id, const std::vector<double>& q,
                const Positions2& positions, Index rows) {
  Mat2 b = Mat2::Zero(rows, 2);
  for (size_t i = 0; i < net.bars.size(); ++i) {
    const auto [u, v] = net.bars[i];
    const Index fu = free_id[u], fv = free_id[v];
    if (fu >= 0 && fv < 0) b.row(fu) += q[i] * positions[v].transpose();
    if (fv >= 0 && fu < 0) b.row(fv) += q[i] * positions[u].transpose();
  }
  return b;
}

Positions2 scatter(const BarNet& net, const std::vector<Index>& free_id, const Mat2& x,
                   const Positions2& fixed) {
  Positions2 out(net.node_count);
  for (Index v = 0; v < net.node_count; ++v) {
    const Index r = free_id[v];
    out[v] = r >= 0 ? Vec2(x(r, 0), x(r, 1)) : fixed[v];
    if (!std::isfinite(out[v].x()) || !std::isfinite(out[v].y()))
      throw Error(ErrorKind::Numeric, "bar net solve produced a non-finite position");
  }
  return out;
}

// K_ff = C_f^T Q C_f, assembled straight into compressed columns (both triangles, rows sorted):
// the diagonal sums q over every bar at the node, in bar order; each bar between two free nodes
// adds -q at (u, v) and (v, u).
SparseMatrix free_matrix(const BarNet& net, const std::vector<Index>& free_id,
                         const std::vector<double>& q, Index rows) {
  std::vector<Index> start(static_cast<size_t>(rows) + 1, 0);
  for (Index r = 0; r < rows; ++r) start[r + 1] = 1;
  for (const auto& [u, v] : net.bars)
    if (free_id[u] >= 0 && free_id[v] >= 0) {
      ++start[free_id[u] + 1];
      ++start[free_id[v] + 1];
    }
  for (Index r = 0; r < rows; ++r) start[r + 1] += start[r];
  SparseMatrix K(rows, rows);
  K.resizeNonZeros(start[rows]);
  Index* outer = K.outerIndexPtr();
  Index* inner = K.innerIndexPtr();
  double* value = K.valuePtr();
  std::copy(start.begin(), start.end(), outer);
  std::vector<Index> next(start.begin(), start.end() - 1);
  for (Index r = 0; r < rows; ++r) {  // the diagonal takes the first slot until the sort below
    inner[next[r]] = r;
    value[next[r]++] = 0.0;
  }
  for (size_t i = 0; i < net.bars.size(); ++i) {
    const Index fu = free_id[net.bars[i][0]], fv = free_id[net.bars[i][1]];
    if (fu >= 0) value[start[fu]] += q[i];
    if (fv >= 0) value[start[fv]] += q[i];
    if (fu >= 0 && fv >= 0) {
      inner[next[fv]] = fu;
      value[next[fv]++] = -q[i];
      inner[next[fu]] = fv;
      value[next[fu]++] = -q[i];
    }
  }
  for (Index c = 0; c < rows; ++c)  // insertion sort: a column holds a node's few neighbours
    for (Index k = start[c] + 1; k < start[c + 1]; ++k)
      for (Index j = k; j > start[c] && inner[j - 1] > inner[j]; --j) {
        std::swap(inner[j - 1], inner[j]);
        std::swap(value[j - 1], value[j]);
      }
  // Two bars between the same nodes (never in a patch, possible in a hand-made net) share an entry.
  Index kept = 0;
  for (Index c = 0; c < rows; ++c) {
    const Index begin = kept;
    for (Index k = start[c]; k < start[c + 1]; ++k) {
      if (kept > begin && inner[kept - 1] == inner[k]) {
        value[kept - 1] += value[k];
      } else {
        inner[kept] = inner[k];
        value[kept++] = value[k];
      }
    }
    outer[c + 1] = kept;
  }
  K.resizeNonZeros(kept);
  return K;
}

// Factorises K on a copy of `symbolic` (the analysis of K's pattern) and solves K x = b.
Mat2 factor_and_solve(const SparseMatrix& K, const Mat2& b, const cholmod_factor* symbolic,
                      Cholmod& c) {
  const Index rows = static_cast<Index>(K.rows());
  cholmod_sparse A = cholmod_view(K);
  cholmod_factor* L = cholmod_copy_factor(const_cast<cholmod_factor*>(symbolic), c.get());
  const bool factored = L && cholmod_factorize(&A, L, c.get()) && c->status == CHOLMOD_OK;
  cholmod_dense B{};
  B.nrow = B.d = static_cast<size_t>(rows);
  B.ncol = 2;
  B.nzmax = 2 * B.nrow;
  B.x = const_cast<double*>(b.data());
  B.xtype = CHOLMOD_REAL;
  B.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* X = factored ? cholmod_solve(CHOLMOD_A, L, &B, c.get()) : nullptr;
  const bool solved = X != nullptr;
  Mat2 x(rows, 2);
  if (solved) std::copy_n(static_cast<const double*>(X->x), 2 * rows, x.data());
  cholmod_free_dense(&X, c.get());
  cholmod_free_factor(&L, c.get());
  if (!factored)
    throw Error(ErrorKind::Numeric, "bar net: the system could not be factorised (singular)");
  if (!solved) throw Error(ErrorKind::Numeric, "bar net: solve failed");
  return x;
}

// K x = b from scratch: ordering, symbolic analysis and factor. The fill-reducing order, if
// wanted, goes to `perm` (rows of K).
Mat2 direct_solve(const SparseMatrix& K, const Mat2& b, std::vector<Index>* perm = nullptr) {
  Cholmod c;
  cholmod_sparse A = cholmod_view(K);
  cholmod_factor* symbolic = analyze_with_nested_dissection(A, c);
  if (!symbolic || c->status != CHOLMOD_OK) {
    cholmod_free_factor(&symbolic, c.get());
    throw Error(ErrorKind::Numeric, "bar net: the symbolic analysis failed");
  }
  if (perm) {
    const Index* p = static_cast<const Index*>(symbolic->Perm);
    perm->assign(p, p + K.rows());
  }
  Mat2 x;
  try {
    x = factor_and_solve(K, b, symbolic, c);
  } catch (...) {
    cholmod_free_factor(&symbolic, c.get());
    throw;
  }
  cholmod_free_factor(&symbolic, c.get());
  return x;
}

// K_ff's pattern with every q = 1: what a frame solver's slots and hierarchy are built from.
SparseMatrix unit_pattern(const BarNet& net, const std::vector<Index>& free_id, Index rows) {
  SparseMatrix K = free_matrix(net, free_id, std::vector<double>(net.bars.size(), 1.0), rows);
  K.makeCompressed();
  return K;
}

// A frame's matrix values: each bar's q added at its four slots, in bar order.
void add_densities(const std::vector<std::array<Index, 4>>& slots, const std::vector<double>& q,
                   double* values) {
  for (size_t i = 0; i < slots.size(); ++i) {
    const auto& s = slots[i];
    if (s[0] >= 0) values[s[0]] += q[i];
    if (s[1] >= 0) values[s[1]] += q[i];
    if (s[2] >= 0) values[s[2]] -= q[i];
    if (s[3] >= 0) values[s[3]] -= q[i];
  }
}

}  // namespace

// The symbolic Cholesky factor of K_ff's pattern, computed once and copied per frame.
struct FrameNetSolver::Symbolic {
  cholmod_factor* L = nullptr;
  ~Symbolic() {
    Cholmod c;
    cholmod_free_factor(&L, c.get());
  }
};

Positions2 solve_bar_net(const BarNet& net, const std::vector<double>& q,
                         const Positions2& positions, std::vector<Index>* node_order) {
  SKINSLIDE_CHECK(q.size() == net.bars.size(), "one q per bar");
  SKINSLIDE_CHECK(positions.size() == static_cast<size_t>(net.node_count), "one position per node");
  const FreeSystem s = free_system(net);
  const Index rows = static_cast<Index>(s.free_nodes.size());
  if (node_order) node_order->clear();
  if (rows == 0) return positions;
  SparseMatrix K = free_matrix(net, s.free_id, q, rows);
  K.makeCompressed();
  const Mat2 b = fixed_pull(net, s.free_id, q, positions, rows);
  std::vector<Index> perm;
  const Mat2 x = direct_solve(K, b, node_order ? &perm : nullptr);
  if (node_order)
    for (Index k : perm) node_order->push_back(s.free_nodes[k]);
  return scatter(net, s.free_id, x, positions);
}

Positions2 solve_bar_net_multigrid(const BarNet& net, const std::vector<double>& q,
                                   const Positions2& positions, double tolerance,
                                   int max_iterations) {
  SKINSLIDE_CHECK(q.size() == net.bars.size(), "one q per bar");
  SKINSLIDE_CHECK(positions.size() == static_cast<size_t>(net.node_count), "one position per node");
  const FreeSystem s = free_system(net);
  const Index rows = static_cast<Index>(s.free_nodes.size());
  if (rows == 0) return positions;
  SparseMatrix K = free_matrix(net, s.free_id, q, rows);
  K.makeCompressed();
  const Mat2 b = fixed_pull(net, s.free_id, q, positions, rows);
  Mat2 x(rows, 2);
  for (Index r = 0; r < rows; ++r) x.row(r) = positions[s.free_nodes[r]].transpose();
  const AggregationMultigrid multigrid(K);
  if (!multigrid.solve(K, b, x, tolerance, max_iterations).converged) x = direct_solve(K, b);
  return scatter(net, s.free_id, x, positions);
}

FrameNetSolver::FrameNetSolver(BarNet net, Positions2 positions, FrameNetMethod method,
                               const std::vector<Index>& node_order)
    : net_(std::move(net)), method_(method), start_(std::move(positions)) {
  SKINSLIDE_CHECK(start_.size() == static_cast<size_t>(net_.node_count), "one position per node");
  FreeSystem s = free_system(net_);
  free_id_ = std::move(s.free_id);
  free_nodes_ = std::move(s.free_nodes);
  const Index rows = static_cast<Index>(free_nodes_.size());
  pattern_ = unit_pattern(net_, free_id_, rows);
  if (rows > 0 && method_ == FrameNetMethod::Multigrid)
    multigrid_ = std::make_shared<const AggregationMultigrid>(pattern_);
  if (rows > 0 && method_ == FrameNetMethod::Cholesky) {
    // A given order is restricted to this net's free nodes: eliminating a principal submatrix in
    // the order of the whole creates no more fill than the whole had.
    std::vector<Index> perm;
    for (Index v : node_order)
      if (v >= 0 && v < net_.node_count && free_id_[v] >= 0) perm.push_back(free_id_[v]);
    Cholmod c;
    if (!node_order.empty()) {
      SKINSLIDE_CHECK(static_cast<Index>(perm.size()) == rows,
                      "the node order has every free node");
      c->method[0].ordering = CHOLMOD_GIVEN;
    }
    cholmod_sparse A = cholmod_view(pattern_);
    auto symbolic = std::make_shared<Symbolic>();
    symbolic->L = node_order.empty() ? analyze_with_nested_dissection(A, c)
                                     : cholmod_analyze_p(&A, perm.data(), nullptr, 0, c.get());
    if (!symbolic->L || c->status != CHOLMOD_OK)
      throw Error(ErrorKind::Numeric, "bar net: the symbolic analysis failed");
    symbolic_ = std::move(symbolic);
  }
  // Where each bar's contributions land in the value array, so a solve only refills values.
  auto slot = [&](Index r, Index c) -> Index {
    if (r < 0 || c < 0) return -1;
    const Index begin = pattern_.outerIndexPtr()[c], end = pattern_.outerIndexPtr()[c + 1];
    const Index* inner = pattern_.innerIndexPtr();
    const Index* it = std::lower_bound(inner + begin, inner + end, r);
    SKINSLIDE_CHECK(it != inner + end && *it == r, "bar entry in the pattern");
    return static_cast<Index>(it - inner);
  };
  slot_.resize(net_.bars.size());
  for (size_t i = 0; i < net_.bars.size(); ++i) {
    const Index fu = free_id_[net_.bars[i][0]], fv = free_id_[net_.bars[i][1]];
    slot_[i] = {slot(fu, fu), slot(fv, fv), fu >= 0 && fv >= 0 ? slot(fu, fv) : -1,
                fu >= 0 && fv >= 0 ? slot(fv, fu) : -1};
  }
  if (multigrid_) {
    const std::vector<Index>& level0 = multigrid_->value_slot();
    std::vector<Index> position(level0.size());
    for (size_t k = 0; k < level0.size(); ++k) position[level0[k]] = static_cast<Index>(k);
    level_slot_ = std::move(slot_);
    slot_.clear();
    for (auto& bar : level_slot_)
      for (Index& k : bar)
        if (k >= 0) k = position[k];
  }
}

FrameNetSolver FrameNetSolver::starting_at(Positions2 positions) && {
  SKINSLIDE_CHECK(positions.size() == static_cast<size_t>(net_.node_count),
                  "one position per node");
  FrameNetSolver out = std::move(*this);
  out.start_ = std::move(positions);
  return out;
}

FrameNetSolution FrameNetSolver::solve(const std::vector<double>& q,
                                       const FrameNetOptions& options) const {
  SKINSLIDE_CHECK(q.size() == net_.bars.size(), "one q per bar");
  FrameNetSolution out;
  const Index rows = static_cast<Index>(free_nodes_.size());
  if (rows == 0) {
    out.positions = start_;
    return out;
  }
  const Mat2 b = fixed_pull(net_, free_id_, q, start_, rows);
  Mat2 x0(rows, 2);
  for (Index r = 0; r < rows; ++r) x0.row(r) = start_[free_nodes_[r]].transpose();
  if (method_ == FrameNetMethod::Multigrid) {
    // The values go straight into the multigrid's order: no copy of the pattern and no gather
    // (about 100 MB less per frame in flight at 1M vertices). Its first residual decides
    // whether the warm start is kept, as the check below does for the other methods.
    std::vector<double> values(multigrid_->value_slot().size(), 0.0);
    add_densities(level_slot_, q, values.data());
    Mat2& x = x0;  // the warm start is solved in place: one copy fewer per frame in flight
    const MultigridResult mg =
        multigrid_->solve(values, b, x, options.cg_tolerance, options.cg_max_iterations);
    out.iterations = mg.iterations;
    out.residual = mg.residual;
    if (!mg.converged) {
      SparseMatrix K = pattern_;
      for (size_t k = 0; k < values.size(); ++k)
        K.valuePtr()[multigrid_->value_slot()[k]] = values[k];
      x = direct_solve(K, b);
      out.direct = true;
    }
    out.positions = scatter(net_, free_id_, x, start_);
    return out;
  }
  SparseMatrix K = pattern_;
  std::fill(K.valuePtr(), K.valuePtr() + K.nonZeros(), 0.0);
  add_densities(slot_, q, K.valuePtr());
  // Keep the warm start when it already meets the tolerance: a frame whose net is the bind net
  // (an undeformed frame) then slides nothing, to the last bit, whatever the method.
  const Mat2 r0 = b - K.selfadjointView<Eigen::Lower>() * x0;
  if (r0.col(0).norm() <= options.cg_tolerance * b.col(0).norm() &&
      r0.col(1).norm() <= options.cg_tolerance * b.col(1).norm()) {
    out.positions = scatter(net_, free_id_, x0, start_);
    return out;
  }
  if (method_ == FrameNetMethod::Cholesky) {
    Cholmod c;
    const Mat2 x = factor_and_solve(K, b, symbolic_->L, c);
    out.positions = scatter(net_, free_id_, x, start_);
    return out;
  }
  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper> cg;
  cg.setTolerance(options.cg_tolerance);
  cg.setMaxIterations(options.cg_max_iterations);
  cg.compute(K);
  Mat2 x(rows, 2);
  bool converged = cg.info() == Eigen::Success;
  for (int c = 0; c < 2 && converged; ++c) {
    x.col(c) = cg.solveWithGuess(b.col(c), x0.col(c));
    converged = cg.info() == Eigen::Success && x.col(c).allFinite();
    out.iterations = std::max(out.iterations, static_cast<int>(cg.iterations()));
    out.residual = std::max(out.residual, cg.error());
  }
  if (!converged) {
    x = direct_solve(K, b);
    out.direct = true;
  }
  out.positions = scatter(net_, free_id_, x, start_);
  return out;
}

}  // namespace skinslide
