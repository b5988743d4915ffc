#include "solve/sparse_cholesky.h"

#include "core/error.h"
#include "solve/cholmod.h"

namespace skinslide {
namespace {

// A simplicial factor's compressed columns, each column's diagonal entry first.
struct Columns {
  const Index* start;
  const Index* row;
  const double* value;
  Index count(Index j) const { return start[j + 1] - start[j]; }
};

// Column j + 1 continues column j's supernode when its pattern is j's without j's diagonal.
bool continues(const Columns& L, Index j) {
  if (L.count(j + 1) != L.count(j) - 1 || L.count(j) < 2 || L.row[L.start[j] + 1] != j + 1)
    return false;
  for (Index p = 1; p < L.count(j); ++p)
    if (L.row[L.start[j] + p] != L.row[L.start[j + 1] + p - 1]) return false;
  return true;
}

// Regroups a simplicial factor into supernodes (fundamental ones: no padding but the diagonal
// blocks' upper parts).
void group_supernodes(const Columns& L, Index n, CholeskyFactor& out) {
  out.column_start.assign(1, 0);
  out.row_start.assign(1, 0);
  out.value_start.assign(1, 0);
  for (Index first = 0; first < n;) {
    Index last = first;
    while (last + 1 < n && continues(L, last)) ++last;
    const Index columns = last - first + 1;
    out.rows.insert(out.rows.end(), L.row + L.start[first], L.row + L.start[first + 1]);
    for (Index c = 0; c < columns; ++c) {
      // Column first + c holds rows c.. of the block; the rows above are the upper part.
      out.value.insert(out.value.end(), static_cast<size_t>(c), 0.0f);
      for (Index p = L.start[first + c]; p < L.start[first + c + 1]; ++p)
        out.value.push_back(static_cast<float>(L.value[p]));
    }
    out.column_start.push_back(last + 1);
    out.row_start.push_back(static_cast<Index>(out.rows.size()));
    out.value_start.push_back(out.value.size());
    first = last + 1;
  }
}

}  // namespace

size_t CholeskyFactor::bytes() const {
  return (order.size() + column_start.size() + row_start.size() + rows.size()) * sizeof(Index) +
         value_start.size() * sizeof(size_t) + value.size() * sizeof(float);
}

CholeskyFactor cholesky_factor(const SymmetricView& A) {
  Cholmod c;
  // LL^T, packed and in column order: plain compressed columns to regroup.
  c->final_ll = 1;
  c->final_pack = 1;
  c->final_monotonic = 1;
  cholmod_sparse view = cholmod_view(A.size, A.start, A.index, A.value);
  cholmod_factor* L = analyze_with_nested_dissection(view, c);
  const bool factored = L && c->status == CHOLMOD_OK && cholmod_factorize(&view, L, c.get()) &&
                        c->status == CHOLMOD_OK && L->minor == L->n;
  CholeskyFactor out;
  if (factored) {
    const Index n = static_cast<Index>(L->n);
    const Index* perm = static_cast<const Index*>(L->Perm);
    out.order.assign(perm, perm + n);
    group_supernodes(Columns{static_cast<const Index*>(L->p), static_cast<const Index*>(L->i),
                             static_cast<const double*>(L->x)},
                     n, out);
  }
  cholmod_free_factor(&L, c.get());
  if (!factored) throw Error(ErrorKind::Numeric, "a sparse matrix is not positive definite");
  return out;
}

void cholesky_solve(const CholeskyFactor& f, Positions2& b, Positions2& y) {
  const Index n = f.size();
  y.resize(n);
  for (Index k = 0; k < n; ++k) y[k] = b[f.order[k]];
  const Index supernodes = static_cast<Index>(f.column_start.size()) - 1;
  // L y = P b, supernode by supernode: the diagonal block, then its rows below.
  for (Index s = 0; s < supernodes; ++s) {
    const Index c0 = f.column_start[s], nc = f.column_start[s + 1] - c0;
    const Index nr = f.row_start[s + 1] - f.row_start[s];
    const Index* rows = f.rows.data() + f.row_start[s];
    const float* L = f.value.data() + f.value_start[s];
    for (Index j = 0; j < nc; ++j, L += nr) {
      const Vec2 yj = y[c0 + j] / static_cast<double>(L[j]);
      y[c0 + j] = yj;
      for (Index i = j + 1; i < nr; ++i) y[rows[i]] -= static_cast<double>(L[i]) * yj;
    }
  }
  // L^T z = y, from the last supernode.
  for (Index s = supernodes - 1; s >= 0; --s) {
    const Index c0 = f.column_start[s], nc = f.column_start[s + 1] - c0;
    const Index nr = f.row_start[s + 1] - f.row_start[s];
    const Index* rows = f.rows.data() + f.row_start[s];
    for (Index j = nc - 1; j >= 0; --j) {
      const float* L = f.value.data() + f.value_start[s] + static_cast<size_t>(j) * nr;
      Vec2 sum = y[c0 + j];
      for (Index i = j + 1; i < nr; ++i) sum -= static_cast<double>(L[i]) * y[rows[i]];
      y[c0 + j] = sum / static_cast<double>(L[j]);
    }
  }
  for (Index k = 0; k < n; ++k) b[f.order[k]] = y[k];
}

}  // namespace skinslide
