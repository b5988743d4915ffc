#include "solve/smoothed_aggregation.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/SparseLU>

namespace skinslide {
namespace {

using Mat2 = Eigen::Matrix<double, Eigen::Dynamic, 2>;
// A row's two columns side by side, added and multiplied lane by lane (as in multigrid.cpp).
using Pair = double __attribute__((vector_size(16)));
using Vec = std::vector<Pair>;

constexpr Index kCoarsestRows = 100;      // factorised directly
constexpr Index kLargestCoarsest = 4000;  // aggregates stalling above this: no hierarchy
constexpr double kStrong = 0.1;           // strong coupling: >= 1/10 of the row's strongest
// The prolongator's damped Jacobi step: omega = kSmoothing / (a Gershgorin bound of the spectral
// radius of D^-1 A): the weight that takes the fewest iterations (against the textbook's 4/3:
// tests/bench/README.md "The elastic bind set-up").
constexpr double kSmoothing = 1.6;

// CSR helpers -----------------------------------------------------------------------------------

// The position of each row's diagonal entry; -1 where it is missing.
std::vector<Index> diagonal_positions(const RowMatrix& A) {
  std::vector<Index> d(A.rows, -1);
  for (Index i = 0; i < A.rows; ++i)
    for (Index k = A.start[i]; k < A.start[i + 1]; ++k)
      if (A.column[k] == i) d[i] = k;
  return d;
}

// Sorts a row's column ids: by insertion when they are a handful, as they mostly are (a hole's
// centre node has a row as long as its loop).
void sort_short(Index* begin, Index* end) {
  if (end - begin > 32) {
    std::sort(begin, end);
    return;
  }
  for (Index* q = begin + 1; q < end; ++q)
    for (Index* p = q; p > begin && *p < *(p - 1); --p) std::swap(*p, *(p - 1));
}

// Ends row i of M with the row a sparse accumulator gathered: its `count` columns in `row`,
// sorted, each with its total.
void append_row(Index* row, Index count, const double* total, Index i, RowMatrix& M) {
  sort_short(row, row + count);
  for (Index q = 0; q < count; ++q) {
    M.column.push_back(row[q]);
    M.value.push_back(total[row[q]]);
  }
  M.start[i + 1] = static_cast<Index>(M.column.size());
}

// C = A B for compressed-row A (rows x inner) and B (inner x columns); columns ascending.
RowMatrix product(const RowMatrix& A, const RowMatrix& B, Index columns) {
  RowMatrix C;
  C.rows = A.rows;
  C.start.resize(static_cast<size_t>(A.rows) + 1);
  std::vector<Index> mark(columns, -1), used(columns);
  std::vector<double> sum(columns, 0.0);
  Index* const marked = mark.data();
  Index* const row = used.data();
  double* const total = sum.data();
  const Index* a_start = A.start.data();
  const Index* a_column = A.column.data();
  const double* a_value = A.value.data();
  const Index* b_start = B.start.data();
  const Index* b_column = B.column.data();
  const double* b_value = B.value.data();
  C.start[0] = 0;
  // Room for the products before merging, or twice A's entries where that is less: enough for
  // the prolongator's products without growing.
  size_t bound = 0;
  for (Index k = 0; k < static_cast<Index>(A.column.size()); ++k)
    bound += static_cast<size_t>(b_start[a_column[k] + 1] - b_start[a_column[k]]);
  bound = std::min(bound, 2 * A.column.size() + static_cast<size_t>(A.rows));
  C.column.reserve(bound);
  C.value.reserve(bound);
  for (Index i = 0; i < A.rows; ++i) {
    Index count = 0;
    for (Index k = a_start[i]; k < a_start[i + 1]; ++k) {
      const Index r = a_column[k];
      const double a = a_value[k];
      for (Index l = b_start[r]; l < b_start[r + 1]; ++l) {
        const Index j = b_column[l];
        if (marked[j] != i) {
          marked[j] = i;
          total[j] = a * b_value[l];
          row[count++] = j;
        } else {
          total[j] += a * b_value[l];
        }
      }
    }
    append_row(row, count, total, i, C);
  }
  return C;
}

// The transpose of a compressed-row matrix with `columns` columns.
RowMatrix transpose(const RowMatrix& A, Index columns) {
  RowMatrix T;
  T.rows = columns;
  T.start.assign(static_cast<size_t>(columns) + 1, 0);
  for (Index j : A.column) ++T.start[j + 1];
  for (Index j = 0; j < columns; ++j) T.start[j + 1] += T.start[j];
  T.column.resize(A.column.size());
  T.value.resize(A.column.size());
  std::vector<Index> next(T.start.begin(), T.start.end() - 1);
  for (Index i = 0; i < A.rows; ++i)
    for (Index k = A.start[i]; k < A.start[i + 1]; ++k) {
      const Index at = next[A.column[k]]++;
      T.column[at] = i;
      T.value[at] = A.value[k];
    }
  return T;
}

// Aggregates, in row order: a row whose strong neighbours are all still free becomes a root
// with them; a row left over joins the root aggregate of its strongest neighbour in one, or else
// starts an aggregate with its free strong neighbours. Returns the number of aggregates.
Index aggregate_rows(const RowMatrix& A, const std::vector<Index>& diagonal,
                     std::vector<Index>& aggregate) {
  const Index n = A.rows;
  std::vector<char> strong(A.column.size(), 0);
  for (Index i = 0; i < n; ++i) {
    double largest = 0;
    for (Index k = A.start[i]; k < A.start[i + 1]; ++k)
      if (k != diagonal[i]) largest = std::max(largest, -A.value[k]);
    for (Index k = A.start[i]; k < A.start[i + 1]; ++k)
      strong[k] = k != diagonal[i] && -A.value[k] > 0 && -A.value[k] >= kStrong * largest;
  }
  aggregate.assign(n, -1);
  Index count = 0;
  for (Index i = 0; i < n; ++i) {
    if (aggregate[i] >= 0) continue;
    bool free = true;
    for (Index k = A.start[i]; k < A.start[i + 1] && free; ++k)
      free = !strong[k] || aggregate[A.column[k]] < 0;
    if (!free) continue;
    aggregate[i] = count;
    for (Index k = A.start[i]; k < A.start[i + 1]; ++k)
      if (strong[k]) aggregate[A.column[k]] = count;
    ++count;
  }
  const std::vector<Index> roots = aggregate;
  for (Index i = 0; i < n; ++i) {
    if (aggregate[i] >= 0) continue;
    double best = 0;
    for (Index k = A.start[i]; k < A.start[i + 1]; ++k)
      if (strong[k] && roots[A.column[k]] >= 0 && -A.value[k] > best) {
        best = -A.value[k];
        aggregate[i] = roots[A.column[k]];
      }
  }
  for (Index i = 0; i < n; ++i) {
    if (aggregate[i] >= 0) continue;
    aggregate[i] = count;
    for (Index k = A.start[i]; k < A.start[i + 1]; ++k)
      if (strong[k] && aggregate[A.column[k]] < 0) aggregate[A.column[k]] = count;
    ++count;
  }
  return count;
}

// P = (I - omega D^-1 A) P0, P0 the aggregates' indicator, omega = kSmoothing / (a Gershgorin
// bound of D^-1 A's spectral radius).
RowMatrix smoothed_prolongator(const RowMatrix& A, const std::vector<double>& inverse_diagonal,
                               const std::vector<Index>& aggregate, Index aggregates) {
  double rho = 0;
  for (Index i = 0; i < A.rows; ++i) {
    double s = 0;
    for (Index k = A.start[i]; k < A.start[i + 1]; ++k) s += std::abs(A.value[k]);
    rho = std::max(rho, s * std::abs(inverse_diagonal[i]));
  }
  const double omega = kSmoothing / rho;
  RowMatrix P;
  P.rows = A.rows;
  P.start.resize(static_cast<size_t>(A.rows) + 1);
  P.start[0] = 0;
  P.column.reserve(A.column.size() / 2);
  P.value.reserve(A.column.size() / 2);
  std::vector<Index> mark(aggregates, -1), used(aggregates);
  std::vector<double> sum(aggregates, 0.0);
  Index* const marked = mark.data();
  Index* const row = used.data();
  double* const total = sum.data();
  for (Index i = 0; i < A.rows; ++i) {
    Index count = 0;
    const double scale = omega * inverse_diagonal[i];
    for (Index k = A.start[i]; k < A.start[i + 1]; ++k) {
      const Index c = aggregate[A.column[k]];
      const double v = (A.column[k] == i ? 1.0 : 0.0) - scale * A.value[k];
      if (marked[c] != i) {
        marked[c] = i;
        total[c] = v;
        row[count++] = c;
      } else {
        total[c] += v;
      }
    }
    append_row(row, count, total, i, P);
  }
  return P;
}

// The hierarchy and its V-cycle ------------------------------------------------------------------

struct Level {
  const RowMatrix* A = nullptr;  // level 0: the caller's matrix; below: `own`
  RowMatrix own;
  std::vector<Index> diagonal;
  std::vector<double> inverse_diagonal;
  RowMatrix P;  // to the next level; empty on the coarsest
  Vec rc, zc;   // the next level's right-hand side and correction
};

class Hierarchy {
 public:
  // False when no usable hierarchy exists (see the header).
  bool build(const RowMatrix& A) {
    levels_.clear();
    levels_.emplace_back();
    levels_.back().A = &A;
    while (true) {
      Level& L = levels_.back();
      const RowMatrix& M = *L.A;
      L.diagonal = diagonal_positions(M);
      L.inverse_diagonal.resize(M.rows);
      for (Index i = 0; i < M.rows; ++i) {
        const double d = L.diagonal[i] >= 0 ? M.value[L.diagonal[i]] : 0.0;
        if (!(d > 0) || !std::isfinite(d)) return false;
        L.inverse_diagonal[i] = 1.0 / d;
      }
      if (M.rows <= kCoarsestRows) break;
      std::vector<Index> aggregate;
      const Index count = aggregate_rows(M, L.diagonal, aggregate);
      if (count * 10 > M.rows * 9) {  // aggregates no longer shrink the matrix
        if (M.rows > kLargestCoarsest) return false;
        break;
      }
      L.P = smoothed_prolongator(M, L.inverse_diagonal, aggregate, count);
      RowMatrix coarse = product(transpose(L.P, count), product(M, L.P, count), count);
      L.rc.resize(count);
      L.zc.resize(count);
      levels_.emplace_back();
      levels_.back().own = std::move(coarse);
      levels_.back().A = &levels_.back().own;
      // emplace_back may have moved the levels: re-point every level's matrix at its own copy.
      for (size_t l = 1; l < levels_.size(); ++l) levels_[l].A = &levels_[l].own;
    }
    const RowMatrix& C = *levels_.back().A;
    std::vector<Triplet> entries;
    entries.reserve(C.column.size());
    for (Index i = 0; i < C.rows; ++i)
      for (Index k = C.start[i]; k < C.start[i + 1]; ++k)
        entries.emplace_back(i, C.column[k], C.value[k]);
    SparseMatrix M(C.rows, C.rows);
    M.setFromTriplets(entries.begin(), entries.end());
    M.makeCompressed();
    coarsest_.compute(M);
    if (coarsest_.info() != Eigen::Success) return false;
    coarse_b_.resize(C.rows, 2);
    return true;
  }

  int levels() const { return static_cast<int>(levels_.size()); }

  // z = an approximation of A_l^{-1} r.
  void cycle(size_t l, const Vec& r, Vec& z) {
    Level& L = levels_[l];
    const RowMatrix& M = *L.A;
    if (l + 1 == levels_.size()) {
      for (Index i = 0; i < M.rows; ++i) coarse_b_.row(i) << r[i][0], r[i][1];
      const Mat2 x = coarsest_.solve(coarse_b_);
      for (Index i = 0; i < M.rows; ++i) z[i] = Pair{x(i, 0), x(i, 1)};
      return;
    }
    const Index n = M.rows;
    const Index* start = M.start.data();
    const Index* column = M.column.data();
    const double* a = M.value.data();
    const Index* diagonal = L.diagonal.data();
    const double* inverse_diagonal = L.inverse_diagonal.data();
    const Index* p_start = L.P.start.data();
    const Index* p_column = L.P.column.data();
    const double* p = L.P.value.data();
    Pair* rc = L.rc.data();
    const Pair* zc = L.zc.data();
    // Gauss-Seidel sweeps wait on the row just solved: its term is kept for last (columns ascend,
    // so the row before is just left of the diagonal and the row after just right of it), so
    // that only one multiply-add stands between two rows.
    // Forward sweep from zero: only the strictly lower part meets values of z.
    Pair last{0, 0};
    for (Index i = 0; i < n; ++i) {
      const Index d = diagonal[i];
      const bool chained = d > start[i] && column[d - 1] == i - 1;
      Pair s = r[i];
      for (Index k = start[i]; k < d - chained; ++k) s -= a[k] * z[column[k]];
      Pair zi = s * inverse_diagonal[i];
      if (chained) zi -= (a[d - 1] * inverse_diagonal[i]) * last;
      z[i] = zi;
      last = zi;
    }
    // The residual is then the strictly upper part's: restricted by P^T as it is formed.
    std::fill(L.rc.begin(), L.rc.end(), Pair{0, 0});
    for (Index i = 0; i < n; ++i) {
      Pair s{0, 0};
      for (Index k = diagonal[i] + 1; k < start[i + 1]; ++k) s -= a[k] * z[column[k]];
      for (Index k = p_start[i]; k < p_start[i + 1]; ++k) rc[p_column[k]] += p[k] * s;
    }
    cycle(l + 1, L.rc, L.zc);
    for (Index i = 0; i < n; ++i) {
      Pair s{0, 0};
      for (Index k = p_start[i]; k < p_start[i + 1]; ++k) s += p[k] * zc[p_column[k]];
      z[i] += s;
    }
    // Backward sweep.
    last = Pair{0, 0};
    for (Index i = n; i-- > 0;) {
      const Index d = diagonal[i];
      const bool chained = d + 1 < start[i + 1] && column[d + 1] == i + 1;
      Pair s = r[i];
      for (Index k = start[i]; k <= d; ++k) s -= a[k] * z[column[k]];
      for (Index k = d + 1 + chained; k < start[i + 1]; ++k) s -= a[k] * z[column[k]];
      Pair zi = z[i] + s * inverse_diagonal[i];
      if (chained) zi -= (a[d + 1] * inverse_diagonal[i]) * last;
      z[i] = zi;
      last = zi;
    }
  }

 private:
  std::vector<Level> levels_;
  Eigen::SparseLU<SparseMatrix> coarsest_;
  Mat2 coarse_b_;
};

// y = A x.
void multiply(const RowMatrix& A, const Vec& x, Vec& y) {
  const Index* start = A.start.data();
  const Index* column = A.column.data();
  const double* a = A.value.data();
  for (Index i = 0; i < A.rows; ++i) {
    Pair s{0, 0};
    for (Index k = start[i]; k < start[i + 1]; ++k) s += a[k] * x[column[k]];
    y[i] = s;
  }
}

// y = A x; returns u'y and w'y per column (sums over alternate rows, then added: a single
// running sum would make every row wait for the one before).
std::array<Pair, 2> multiply_dot(const RowMatrix& A, const Vec& x, Vec& y, const Vec& u,
                                 const Vec& w) {
  const Index* start = A.start.data();
  const Index* column = A.column.data();
  const double* a = A.value.data();
  Pair uy[2]{}, wy[2]{};
  for (Index i = 0; i < A.rows; ++i) {
    Pair s{0, 0};
    for (Index k = start[i]; k < start[i + 1]; ++k) s += a[k] * x[column[k]];
    y[i] = s;
    uy[i & 1] += u[i] * s;
    wy[i & 1] += w[i] * s;
  }
  return {uy[0] + uy[1], wy[0] + wy[1]};
}

// u'v per column, four running sums added at the end.
Pair dot(const Vec& u, const Vec& v) {
  Pair s[4]{};
  const size_t n = u.size();
  size_t i = 0;
  for (; i + 4 <= n; i += 4)
    for (size_t c = 0; c < 4; ++c) s[c] += u[i + c] * v[i + c];
  for (; i < n; ++i) s[0] += u[i] * v[i];
  return (s[0] + s[1]) + (s[2] + s[3]);
}

bool finite(Pair p) { return std::isfinite(p[0]) && std::isfinite(p[1]); }

}  // namespace

IterativeSolve solve_smoothed_aggregation(const RowMatrix& A, const Mat2& b, Mat2& x,
                                          double tolerance, int max_iterations) {
  IterativeSolve out;
  const Index n = A.rows;
  if (n == 0) {
    out.converged = true;
    return out;
  }
  Hierarchy M;
  if (!M.build(A)) return out;
  out.levels = M.levels();
  Vec xv(n), bv(n), r(n), r0(n), p(n), v(n), t(n), ph(n), sh(n);
  Vec& s = r;  // s = r - alpha v replaces r, which is formed again from s
  for (Index i = 0; i < n; ++i) {
    xv[i] = Pair{x(i, 0), x(i, 1)};
    bv[i] = Pair{b(i, 0), b(i, 1)};
  }
  const Pair bb = dot(bv, bv);
  Pair bound;  // |r|^2 at convergence, per column
  for (int c = 0; c < 2; ++c) bound[c] = tolerance * tolerance * bb[c];
  auto relative = [&](Pair rr) {
    double worst = 0;
    for (int c = 0; c < 2; ++c)
      worst = std::max(worst, bb[c] > 0 ? std::sqrt(rr[c] / bb[c]) : std::sqrt(rr[c]));
    return worst;
  };
  // BiCGSTAB, restarted from the true residual when the recurrence's residual claims convergence
  // that the true one does not confirm.
  int it = 0;
  while (true) {
    multiply(A, xv, r);
    for (Index i = 0; i < n; ++i) r[i] = bv[i] - r[i];
    Pair rr = dot(r, r);
    out.residual = relative(rr);
    out.iterations = it;
    if (!finite(rr)) return out;
    if (rr[0] <= bound[0] && rr[1] <= bound[1]) {
      out.converged = true;
      break;
    }
    if (it >= max_iterations) break;
    r0 = r;
    Pair rho_next = rr;  // r0'r
    std::fill(p.begin(), p.end(), Pair{0, 0});
    std::fill(v.begin(), v.end(), Pair{0, 0});
    Pair rho{1, 1}, alpha{1, 1}, omega{1, 1};
    bool breakdown = false;
    while (it < max_iterations) {
      bool active[2];
      for (int c = 0; c < 2; ++c) active[c] = rr[c] > bound[c];
      if (!active[0] && !active[1]) break;
      ++it;
      Pair beta{0, 0};
      for (int c = 0; c < 2; ++c) {
        if (!active[c]) continue;
        if (!(rho_next[c] != 0) || !(omega[c] != 0)) breakdown = true;
        beta[c] = (rho_next[c] / rho[c]) * (alpha[c] / omega[c]);
      }
      if (breakdown) break;
      rho = rho_next;
      for (Index i = 0; i < n; ++i) p[i] = r[i] + beta * (p[i] - omega * v[i]);
      M.cycle(0, p, ph);
      const Pair r0v = multiply_dot(A, ph, v, r0, r0)[0];
      for (int c = 0; c < 2; ++c) {
        alpha[c] = active[c] && r0v[c] != 0 ? rho[c] / r0v[c] : 0.0;
        if (active[c] && !(r0v[c] != 0)) breakdown = true;
      }
      if (breakdown) break;
      for (Index i = 0; i < n; ++i) s[i] -= alpha * v[i];
      M.cycle(0, s, sh);
      const auto [ts, tt] = multiply_dot(A, sh, t, s, t);
      for (int c = 0; c < 2; ++c) omega[c] = active[c] && tt[c] > 0 ? ts[c] / tt[c] : 0.0;
      Pair sums[2][2]{};  // r'r and r0'r over alternate rows
      for (Index i = 0; i < n; ++i) {
        xv[i] += alpha * ph[i] + omega * sh[i];
        const Pair ri = s[i] - omega * t[i];
        r[i] = ri;  // over s[i], read for the last time
        sums[i & 1][0] += ri * ri;
        sums[i & 1][1] += r0[i] * ri;
      }
      rr = sums[0][0] + sums[1][0];
      rho_next = sums[0][1] + sums[1][1];
      if (!finite(rr)) return out;
    }
    if (breakdown) break;
  }
  for (Index i = 0; i < n; ++i) x.row(i) << xv[i][0], xv[i][1];
  if (!out.converged) {
    // Report the true residual of the x handed back.
    multiply(A, xv, r);
    for (Index i = 0; i < n; ++i) r[i] = bv[i] - r[i];
    out.residual = relative(dot(r, r));
  }
  return out;
}

}  // namespace skinslide
