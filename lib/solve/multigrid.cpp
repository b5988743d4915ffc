#include "solve/multigrid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

#include <Eigen/SparseCholesky>

#include "core/check.h"

namespace skinslide {
namespace {

using Level = AggregationMultigrid::Level;
using Mat2 = Eigen::Matrix<double, Eigen::Dynamic, 2>;

// Matrix values, one per nonzero of a level.
using Values = std::vector<double>;
// A row's x and y side by side, added and multiplied lane by lane: one instruction does what the
// two columns did one after the other, with the same roundings in the same order (no fused
// multiply-add), so the bits are those of the two scalar columns.
using Pair = double __attribute__((vector_size(16)));
using Vec = std::vector<Pair>;

constexpr Index kCoarsestRows = 200;      // solved by a sparse factorisation
constexpr double kStrongCoupling = 0.25;  // a neighbour is strong at >= 1/4 of the row's largest
constexpr double kInnerReduction = 0.5;   // K-cycle: one inner iteration suffices below this
// Stagnation: a solve gives up when kStallWindow iterations cut the residual by less than
// kStallReduction. A frame net takes 14-28 iterations in all; nets whose densities jump by
// many orders of magnitude between neighbours can take hundreds.
constexpr int kStallWindow = 20;
constexpr double kStallReduction = 10.0;

// Pairs each row with its strongest unpaired neighbour among those coupled at least `strong`
// times as strongly as the row's strongest, in row order (deterministic). Returns the pair index
// of every row and the number of pairs (singletons count as pairs of one).
Index pair_rows(const Level& level, const Values& value, double strong, std::vector<Index>& pair) {
  const Index n = level.rows;
  pair.assign(n, -1);
  Index pairs = 0;
  for (Index i = 0; i < n; ++i) {
    if (pair[i] >= 0) continue;
    double largest = 0;
    for (Index k = level.start[i]; k < level.start[i + 1]; ++k)
      if (level.column[k] != i) largest = std::max(largest, -value[k]);
    Index best = -1;
    double best_value = 0;
    for (Index k = level.start[i]; k < level.start[i + 1]; ++k) {
      const Index j = level.column[k];
      if (j == i || pair[j] >= 0) continue;
      const double a = -value[k];
      if (a >= strong * largest && a > best_value) {
        best = j;
        best_value = a;
      }
    }
    pair[i] = pairs;
    if (best >= 0) pair[best] = pairs;
    ++pairs;
  }
  return pairs;
}

// The pattern of P^T A P for piecewise-constant P (rows summed by aggregate); `slot` receives
// where each fine nonzero lands in it.
Level coarse_level(const Level& fine, const std::vector<Index>& aggregate, Index coarse_rows,
                   std::vector<Index>& slot) {
  Level coarse;
  coarse.rows = coarse_rows;
  // Fine rows grouped by aggregate (counting sort), then each coarse row's columns collected.
  std::vector<Index> first(coarse_rows + 1, 0), members(fine.rows);
  for (Index i = 0; i < fine.rows; ++i) ++first[aggregate[i] + 1];
  for (Index c = 0; c < coarse_rows; ++c) first[c + 1] += first[c];
  {
    std::vector<Index> next(first.begin(), first.end() - 1);
    for (Index i = 0; i < fine.rows; ++i) members[next[aggregate[i]]++] = i;
  }
  coarse.start.assign(1, 0);
  slot.assign(fine.column.size(), -1);
  std::vector<Index> slot_of(coarse_rows, -1);  // coarse column -> slot in the current coarse row
  std::vector<Index> columns;
  for (Index c = 0; c < coarse_rows; ++c) {
    columns.clear();
    for (Index m = first[c]; m < first[c + 1]; ++m) {
      const Index i = members[m];
      for (Index k = fine.start[i]; k < fine.start[i + 1]; ++k) {
        const Index cj = aggregate[fine.column[k]];
        if (slot_of[cj] < 0) {
          slot_of[cj] = 0;
          columns.push_back(cj);
        }
      }
    }
    std::sort(columns.begin(), columns.end());
    const Index base = static_cast<Index>(coarse.column.size());
    for (size_t s = 0; s < columns.size(); ++s) {
      slot_of[columns[s]] = base + static_cast<Index>(s);
      coarse.column.push_back(columns[s]);
      if (columns[s] == c) coarse.diagonal.push_back(base + static_cast<Index>(s));
    }
    for (Index m = first[c]; m < first[c + 1]; ++m) {
      const Index i = members[m];
      for (Index k = fine.start[i]; k < fine.start[i + 1]; ++k)
        slot[k] = slot_of[aggregate[fine.column[k]]];
    }
    for (Index cj : columns) slot_of[cj] = -1;
    coarse.start.push_back(static_cast<Index>(coarse.column.size()));
  }
  return coarse;
}

// The values of P^T A P: each fine value summed into its slot.
Values coarse_values(const std::vector<Index>& slot, const double* value, size_t coarse_nonzeros) {
  Values out(coarse_nonzeros, 0.0);
  for (size_t k = 0; k < slot.size(); ++k) out[slot[k]] += value[k];
  return out;
}

// Both columns' dot products in one pass.
Pair dot(const Vec& a, const Vec& b) {
  Pair s{0, 0};
  for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

// y = A x. Returns x.y per column, then x.u for each u in `also`, summed in the same pass and
// in the same order as dot() sums them: one pass over x where separate products would take more.
template <size_t K = 0>
std::array<Pair, K + 1> multiply(const Level& L, const double* A, const Vec& x, Vec& y,
                                 const std::array<const Vec*, K>& also = {}) {
  const Index* start = L.start.data();
  const Index* column = L.column.data();
  std::array<Pair, K + 1> sums{};
  for (Index i = 0; i < L.rows; ++i) {
    Pair s{0, 0};
    for (Index k = start[i]; k < start[i + 1]; ++k) s += A[k] * x[column[k]];
    y[i] = s;
    sums[0] += x[i] * s;
    for (size_t u = 0; u < K; ++u) sums[u + 1] += x[i] * (*also[u])[i];
  }
  return sums;
}

// The per-solve values: every level's matrix, the coarsest level's factor, and work vectors.
// A level's vectors are reused by every visit: visits to one level never overlap.
struct Numeric {
  const std::vector<Level>* levels;
  std::vector<const double*> value;  // level 0: the caller's matrix; below: coarse_value
  std::vector<Values> coarse_value;
  std::vector<Values> inverse_diagonal;  // a sweep multiplies: a division would lengthen the chain
  Eigen::SimplicialLDLT<SparseMatrix> coarsest;
  struct Work {
    Vec rc, zc;              // kcycle: the restricted residual and its correction (next level)
    Vec c1, v1, r2, c2, v2;  // coarse_correction on this level
  };
  std::vector<Work> work;
};

void kcycle(Numeric& N, size_t l, const Vec& r, Vec& z, Vec* az = nullptr);

// Per column: a / b where b > 0, else 0.
Pair ratio_where_positive(Pair a, Pair b) {
  Pair out{0, 0};
  for (int c = 0; c < 2; ++c) out[c] = b[c] > 0 ? a[c] / b[c] : 0.0;
  return out;
}

// Approximates the solution of A_l zc = rc by two steps of flexible CG preconditioned by the
// next K-cycle (one when the first already reduces the residual enough).
void coarse_correction(Numeric& N, size_t l, const Vec& rc, Vec& zc) {
  Numeric::Work& w = N.work[l];
  const size_t n = rc.size();
  kcycle(N, l, rc, w.c1, &w.v1);
  Pair rho1{0, 0}, alpha1{0, 0};
  for (size_t i = 0; i < n; ++i) {
    rho1 += w.c1[i] * w.v1[i];
    alpha1 += w.c1[i] * rc[i];
  }
  const Pair t1 = ratio_where_positive(alpha1, rho1);
  Pair r2norm{0, 0}, rcnorm{0, 0};
  w.r2.resize(n);
  for (size_t i = 0; i < n; ++i) {
    w.r2[i] = rc[i] - t1 * w.v1[i];
    r2norm += w.r2[i] * w.r2[i];
    rcnorm += rc[i] * rc[i];
  }
  const double enough = kInnerReduction * kInnerReduction;
  if (r2norm[0] <= enough * rcnorm[0] && r2norm[1] <= enough * rcnorm[1]) {
    for (size_t i = 0; i < n; ++i) zc[i] = t1 * w.c1[i];
    return;
  }
  kcycle(N, l, w.r2, w.c2, &w.v2);
  Pair beta{0, 0}, gamma{0, 0}, alpha2{0, 0};
  for (size_t i = 0; i < n; ++i) {
    beta += w.c2[i] * w.v2[i];
    gamma += w.c2[i] * w.v1[i];
    alpha2 += w.c2[i] * w.r2[i];
  }
  Pair f1{0, 0}, f2{0, 0};
  for (int c = 0; c < 2; ++c) {
    if (!(rho1[c] > 0)) continue;
    const double rho2 = beta[c] - gamma[c] * gamma[c] / rho1[c];
    f1[c] = rho2 > 0 ? t1[c] - gamma[c] * alpha2[c] / (rho1[c] * rho2) : t1[c];
    f2[c] = rho2 > 0 ? alpha2[c] / rho2 : 0.0;
  }
  for (size_t i = 0; i < n; ++i) zc[i] = f1 * w.c1[i] + f2 * w.c2[i];
}

// Backward Gauss-Seidel on z. With kProduct it also leaves A z in az: row i's products with the
// rows after it use their final z and are the sweep's own; once z_i is final, the rows after it
// get its products, by symmetry, the terms their own sweep step could not see yet. A coarse-grid
// step needs A z right after its K-cycle: this spares it a pass over the level's matrix. Either
// way z gets the same bits.
template <bool kProduct>
void backward_sweep(const Level& L, const double* A, const double* inverse_diagonal, const Vec& r,
                    Vec& z, Vec* az) {
  const Index* start = L.start.data();
  const Index* column = L.column.data();
  const Index* diagonal = L.diagonal.data();
  if constexpr (kProduct) std::fill(az->begin(), az->end(), Pair{0, 0});
  for (Index i = L.rows; i-- > 0;) {
    Pair s = r[i], after{0, 0};
    for (Index k = start[i]; k <= diagonal[i]; ++k) s -= A[k] * z[column[k]];
    for (Index k = diagonal[i] + 1; k < start[i + 1]; ++k) {
      const Pair t = A[k] * z[column[k]];
      s -= t;
      if constexpr (kProduct) after += t;
    }
    const Pair zi = z[i] + s * inverse_diagonal[i];
    z[i] = zi;
    if constexpr (kProduct) {
      Vec& v = *az;
      v[i] += after + A[diagonal[i]] * zi;
      for (Index k = diagonal[i] + 1; k < start[i + 1]; ++k) v[column[k]] += A[k] * zi;
    }
  }
}

// z = an approximation of A_l^{-1} r: forward Gauss-Seidel from zero, coarse correction, backward
// Gauss-Seidel (a symmetric smoother around the correction).
void kcycle(Numeric& N, size_t l, const Vec& r, Vec& z, Vec* az) {
  const std::vector<Level>& levels = *N.levels;
  const Level& L = levels[l];
  const double* A = N.value[l];
  if (l + 1 == levels.size()) {
    Mat2 rhs(L.rows, 2);
    for (Index i = 0; i < L.rows; ++i) rhs.row(i) << r[i][0], r[i][1];
    const Mat2 sol = N.coarsest.solve(rhs);
    for (Index i = 0; i < L.rows; ++i) z[i] = Pair{sol(i, 0), sol(i, 1)};
    if (az) multiply(L, A, z, *az);
    return;
  }
  const Index* start = L.start.data();
  const Index* column = L.column.data();
  const Index* diagonal = L.diagonal.data();
  const Index* aggregate = L.aggregate.data();
  const double* inverse_diagonal = N.inverse_diagonal[l].data();
  // From zero, the forward sweep reads only the strictly lower part, and afterwards row j's
  // residual is what the strictly upper part takes: -sum_{i>j} a_ji z_i. A is symmetric, so row
  // i's strictly lower entries are those terms of the rows before it: each is restricted as
  // soon as z_i is known, in the same pass instead of a second half pass (tests/bench/README.md
  // "Performance"). On coarse levels a_ij and a_ji are sums of the same fine values in different
  // orders and may differ in the last bit: a preconditioner need not be exact.
  Numeric::Work& w = N.work[l];
  std::fill(w.rc.begin(), w.rc.end(), Pair{0, 0});
  for (Index i = 0; i < L.rows; ++i) {
    Pair s = r[i];
    for (Index k = start[i]; k < diagonal[i]; ++k) s -= A[k] * z[column[k]];
    const Pair zi = s * inverse_diagonal[i];
    z[i] = zi;
    for (Index k = start[i]; k < diagonal[i]; ++k) w.rc[aggregate[column[k]]] -= A[k] * zi;
  }
  if (l + 2 == levels.size())
    kcycle(N, l + 1, w.rc, w.zc);
  else
    coarse_correction(N, l + 1, w.rc, w.zc);
  for (Index i = 0; i < L.rows; ++i) z[i] += w.zc[aggregate[i]];
  if (az)
    backward_sweep<true>(L, A, inverse_diagonal, r, z, az);
  else
    backward_sweep<false>(L, A, inverse_diagonal, r, z, az);
}

// The top level's sweep order: A's rows in Cuthill-McKee order, breadth first from a far end of
// the net, neighbours by ascending degree (ties by row). The sweeps then cross the net as a
// front, whatever order the file had its vertices in: a row's neighbours are near it in memory,
// most rows have as many neighbours before them as the row before (the loops exit where the
// processor predicts), and Gauss-Seidel along a front smooths better than along the file's
// order (tests/bench/README.md "Performance"). Components one after another, each from the
// far end of its lowest row.
std::vector<Index> cuthill_mckee_order(const SparseMatrix& A) {
  const Index n = static_cast<Index>(A.rows());
  const Index* start = A.outerIndexPtr();
  const Index* row = A.innerIndexPtr();
  auto degree = [&](Index i) { return start[i + 1] - start[i]; };
  std::vector<Index> order, level(n, -1), neighbours;
  order.reserve(n);
  // Breadth-first from `root` over the unvisited rows, appending them to `order`; returns the
  // position in `order` where this search began.
  auto search = [&](Index root) {
    const size_t begin = order.size();
    level[root] = 0;
    order.push_back(root);
    for (size_t head = begin; head < order.size(); ++head) {
      const Index i = order[head];
      neighbours.clear();
      for (Index k = start[i]; k < start[i + 1]; ++k)
        if (level[row[k]] < 0) {
          level[row[k]] = level[i] + 1;
          neighbours.push_back(row[k]);
        }
      std::sort(neighbours.begin(), neighbours.end(), [&](Index a, Index b) {
        return degree(a) != degree(b) ? degree(a) < degree(b) : a < b;
      });
      order.insert(order.end(), neighbours.begin(), neighbours.end());
    }
    return begin;
  };
  // Undoes a search: its rows become unvisited again.
  auto forget = [&](size_t begin) {
    for (size_t k = begin; k < order.size(); ++k) level[order[k]] = -1;
    order.resize(begin);
  };
  for (Index first = 0; first < n; ++first) {
    if (level[first] >= 0) continue;
    // A far end of the component: the last row of a search from its lowest row, the
    // lowest-degree row of the deepest level breaking ties (George & Liu's first step).
    size_t begin = search(first);
    Index root = order.back();
    for (size_t k = begin; k < order.size(); ++k)
      if (level[order[k]] == level[order.back()] &&
          (degree(order[k]) < degree(root) ||
           (degree(order[k]) == degree(root) && order[k] < root)))
        root = order[k];
    forget(begin);
    search(root);
  }
  return order;
}

// The pattern of A with rows and columns renumbered so that new row i is A's row order[i];
// slot[k] is A's nonzero that new nonzero k holds.
Level permuted_pattern(const SparseMatrix& A, const std::vector<Index>& order,
                       std::vector<Index>& slot) {
  const Index n = static_cast<Index>(A.rows());
  std::vector<Index> new_id(n);
  for (Index i = 0; i < n; ++i) new_id[order[i]] = i;
  Level L;
  L.rows = n;
  L.start.assign(1, 0);
  std::vector<std::pair<Index, Index>> row;  // (new column, A's nonzero)
  for (Index i = 0; i < n; ++i) {
    row.clear();
    for (Index k = A.outerIndexPtr()[order[i]]; k < A.outerIndexPtr()[order[i] + 1]; ++k)
      row.push_back({new_id[A.innerIndexPtr()[k]], k});
    std::sort(row.begin(), row.end());
    Index diagonal = -1;
    for (const auto& [c, k] : row) {
      if (c == i) diagonal = static_cast<Index>(L.column.size());
      L.column.push_back(c);
      slot.push_back(k);
    }
    SKINSLIDE_CHECK(diagonal >= 0, "every row has a diagonal entry");
    L.diagonal.push_back(diagonal);
    L.start.push_back(static_cast<Index>(L.column.size()));
  }
  return L;
}

}  // namespace

AggregationMultigrid::AggregationMultigrid(const SparseMatrix& A) {
  SKINSLIDE_CHECK(A.rows() == A.cols() && A.isCompressed(), "a square compressed matrix");
  order_ = cuthill_mckee_order(A);
  levels_.push_back(permuted_pattern(A, order_, value_slot_));
  Values value(value_slot_.size());
  for (size_t k = 0; k < value.size(); ++k) value[k] = A.valuePtr()[value_slot_[k]];
  // Each level pairs twice (aggregates of up to four rows) until the coarsest is small. Where
  // strong couplings leave too many rows unpaired (couplings that jump by orders of magnitude),
  // the level pairs again with any coupled neighbour; a level that still stalls is the
  // coarsest, whatever its size (its factor is sparse).
  while (levels_.back().rows > kCoarsestRows) {
    const Level& fine = levels_.back();
    std::vector<Index> aggregate(fine.rows);
    Index quads = 0;
    for (double strong : {kStrongCoupling, 0.0}) {
      std::vector<Index> first_pair, second_pair, mid_slot;
      const Index pairs = pair_rows(fine, value, strong, first_pair);
      const Level mid = coarse_level(fine, first_pair, pairs, mid_slot);
      const Values mid_value = coarse_values(mid_slot, value.data(), mid.column.size());
      quads = pair_rows(mid, mid_value, strong, second_pair);
      for (Index i = 0; i < fine.rows; ++i) aggregate[i] = second_pair[first_pair[i]];
      if (quads * 3 <= fine.rows * 2) break;  // at least 1.5x coarser
    }
    if (quads * 3 > fine.rows * 2) break;
    std::vector<Index> slot;
    Level coarse = coarse_level(fine, aggregate, quads, slot);
    value = coarse_values(slot, value.data(), coarse.column.size());
    levels_.back().aggregate = std::move(aggregate);
    levels_.back().coarse_slot = std::move(slot);
    levels_.push_back(std::move(coarse));
  }
}

MultigridResult AggregationMultigrid::solve(const SparseMatrix& A, const Mat2& b, Mat2& x,
                                            double tolerance, int max_iterations) const {
  SKINSLIDE_CHECK(
      A.rows() == levels_.front().rows && A.nonZeros() == static_cast<Index>(value_slot_.size()),
      "the matrix has the hierarchy's pattern");
  Values top_value(value_slot_.size());
  for (size_t k = 0; k < top_value.size(); ++k) top_value[k] = A.valuePtr()[value_slot_[k]];
  return solve(top_value, b, x, tolerance, max_iterations);
}

MultigridResult AggregationMultigrid::solve(const std::vector<double>& level0_values, const Mat2& b,
                                            Mat2& x, double tolerance, int max_iterations) const {
  const Level& top = levels_.front();
  SKINSLIDE_CHECK(
      level0_values.size() == top.column.size() && b.rows() == top.rows && x.rows() == top.rows,
      "values and vectors of the hierarchy's size");
  Numeric N;
  N.levels = &levels_;
  N.value.resize(levels_.size());
  N.value[0] = level0_values.data();
  N.coarse_value.resize(levels_.size());
  for (size_t l = 0; l + 1 < levels_.size(); ++l) {
    N.coarse_value[l + 1] =
        coarse_values(levels_[l].coarse_slot, N.value[l], levels_[l + 1].column.size());
    N.value[l + 1] = N.coarse_value[l + 1].data();
  }
  {
    const Level& C = levels_.back();
    // Compressed rows of a symmetric matrix are its compressed columns.
    const Eigen::Map<const SparseMatrix> coarsest(C.rows, C.rows,
                                                  static_cast<Index>(C.column.size()),
                                                  C.start.data(), C.column.data(), N.value.back());
    N.coarsest.compute(coarsest);
    // A singular system (a part with no fixed node) or non-finite values: not solvable here.
    if (N.coarsest.info() != Eigen::Success) return {};
  }
  N.inverse_diagonal.resize(levels_.size());
  for (size_t l = 0; l < levels_.size(); ++l) {
    N.inverse_diagonal[l].resize(levels_[l].rows);
    for (Index i = 0; i < levels_[l].rows; ++i)
      N.inverse_diagonal[l][i] = 1.0 / N.value[l][levels_[l].diagonal[i]];
  }
  N.work.resize(levels_.size());
  for (size_t l = 0; l < levels_.size(); ++l) {
    const size_t n = static_cast<size_t>(levels_[l].rows);
    Numeric::Work& w = N.work[l];
    if (l + 1 < levels_.size()) {
      w.rc.resize(static_cast<size_t>(levels_[l + 1].rows));
      w.zc.resize(w.rc.size());
    }
    if (l > 0) {
      w.c1.resize(n), w.v1.resize(n), w.c2.resize(n), w.v2.resize(n);
    }
  }
  const size_t n = static_cast<size_t>(top.rows);
  Vec xv(n), bv(n), r(n);
  for (Index i = 0; i < top.rows; ++i) {
    xv[i] = Pair{x(order_[i], 0), x(order_[i], 1)};
    bv[i] = Pair{b(order_[i], 0), b(order_[i], 1)};
  }
  multiply(top, N.value[0], xv, r);
  for (size_t i = 0; i < n; ++i) r[i] = bv[i] - r[i];
  const Pair bb = dot(bv, bv);
  Vec().swap(bv);  // not read again: the vectors below can take its memory
  Vec z(n), p(n), q(n);
  Pair rr = dot(r, r), pq_previous{0, 0};
  MultigridResult out;
  std::vector<double> history;  // the worse column's relative residual per iteration
  for (int it = 0;; ++it) {
    bool active[2];
    double worst = 0;
    for (int c = 0; c < 2; ++c) {
      active[c] = std::sqrt(rr[c]) > tolerance * std::sqrt(bb[c]);
      worst = std::max(worst, bb[c] > 0 ? std::sqrt(rr[c] / bb[c]) : std::sqrt(rr[c]));
    }
    out.residual = worst;
    out.iterations = it;
    history.push_back(worst);
    if (!std::isfinite(worst)) break;
    if (!active[0] && !active[1]) {
      out.converged = true;
      break;
    }
    if (it == max_iterations) break;
    if (it >= kStallWindow && worst * kStallReduction > history[it - kStallWindow]) break;
    kcycle(N, 0, r, z);
    // Flexible CG: p is made A-orthogonal to the previous p (the K-cycle is not a fixed linear
    // operator). A converged column keeps its x and r.
    const Pair zq = it > 0 ? dot(z, q) : Pair{0, 0};
    const Pair beta = ratio_where_positive(-zq, pq_previous);
    for (size_t i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
    const auto [pq, pr] = multiply<1>(top, N.value[0], p, q, {&r});
    Pair alpha{0, 0};
    for (int c = 0; c < 2; ++c) alpha[c] = active[c] && pq[c] > 0 ? pr[c] / pq[c] : 0.0;
    pq_previous = pq;
    rr = Pair{0, 0};
    for (size_t i = 0; i < n; ++i) {
      xv[i] += alpha * p[i];
      r[i] -= alpha * q[i];
      rr += r[i] * r[i];
    }
  }
  for (Index i = 0; i < top.rows; ++i) x.row(order_[i]) << xv[i][0], xv[i][1];
  return out;
}

}  // namespace skinslide
