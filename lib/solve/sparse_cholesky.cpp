#include "solve/sparse_cholesky.h"

#include "core/error.h"
#include "solve/cholmod.h"

namespace skinslide {

size_t CholeskyFactor::bytes() const {
  return order.size() * sizeof(Index) + column_start.size() * sizeof(Index) +
         row.size() * sizeof(Index) + value.size() * sizeof(float);
}

CholeskyFactor cholesky_factor(const SparseMatrix& A) {
  Cholmod c;
  // LL^T, packed and in column order: plain compressed columns to copy out.
  c->final_ll = 1;
  c->final_pack = 1;
  c->final_monotonic = 1;
  cholmod_sparse view = cholmod_view(A);
  cholmod_factor* L = analyze_with_nested_dissection(view, c);
  const bool factored = L && c->status == CHOLMOD_OK && cholmod_factorize(&view, L, c.get()) &&
                        c->status == CHOLMOD_OK && L->minor == L->n;
  CholeskyFactor out;
  if (factored) {
    const size_t n = L->n;
    const Index* perm = static_cast<const Index*>(L->Perm);
    const Index* p = static_cast<const Index*>(L->p);
    const Index* i = static_cast<const Index*>(L->i);
    const double* x = static_cast<const double*>(L->x);
    out.order.assign(perm, perm + n);
    out.column_start.assign(p, p + n + 1);
    out.row.assign(i, i + p[n]);
    out.value.assign(x, x + p[n]);
  }
  cholmod_free_factor(&L, c.get());
  if (!factored) throw Error(ErrorKind::Numeric, "a sparse matrix is not positive definite");
  return out;
}

void cholesky_solve(const CholeskyFactor& f, Positions2& b, Positions2& y) {
  const Index n = f.size();
  y.resize(n);
  for (Index k = 0; k < n; ++k) y[k] = b[f.order[k]];
  const Index* start = f.column_start.data();
  const Index* row = f.row.data();
  const float* value = f.value.data();
  // L y = P b, column by column (the diagonal first in each).
  for (Index j = 0; j < n; ++j) {
    const Vec2 yj = y[j] / static_cast<double>(value[start[j]]);
    y[j] = yj;
    for (Index p = start[j] + 1; p < start[j + 1]; ++p)
      y[row[p]] -= static_cast<double>(value[p]) * yj;
  }
  // L^T z = y, from the last column.
  for (Index j = n - 1; j >= 0; --j) {
    Vec2 s = y[j];
    for (Index p = start[j] + 1; p < start[j + 1]; ++p)
      s -= static_cast<double>(value[p]) * y[row[p]];
    y[j] = s / static_cast<double>(value[start[j]]);
  }
  for (Index k = 0; k < n; ++k) b[f.order[k]] = y[k];
}

}  // namespace skinslide
