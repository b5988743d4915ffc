#include "solve/cholmod.h"

#include <mutex>

#include "core/check.h"

namespace skinslide {

Cholmod::Cholmod() {
  cholmod_start(&c_);
  c_.nmethods = 1;
  c_.method[0].ordering = CHOLMOD_NESDIS;
  c_.postorder = 1;
  c_.supernodal = CHOLMOD_SIMPLICIAL;
  c_.print = 0;
}

Cholmod::~Cholmod() { cholmod_finish(&c_); }

cholmod_sparse cholmod_view(Index size, const Index* start, const Index* index,
                            const double* value) {
  cholmod_sparse A{};
  A.nrow = A.ncol = static_cast<size_t>(size);
  A.nzmax = static_cast<size_t>(start[size]);
  A.p = const_cast<Index*>(start);
  A.i = const_cast<Index*>(index);
  A.x = const_cast<double*>(value);
  A.stype = -1;
  A.itype = CHOLMOD_INT;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  return A;
}

cholmod_sparse cholmod_view(const SparseMatrix& K) {
  SKINSLIDE_CHECK(K.isCompressed(), "CHOLMOD reads a compressed matrix");
  return cholmod_view(static_cast<Index>(K.rows()), K.outerIndexPtr(), K.innerIndexPtr(),
                      K.valuePtr());
}

// METIS, which finds the separators, keeps state between calls outside the call (its random
// number generator), so two patches ordered at once by two threads get orders, and so factors,
// that depend on the timing: one ordering at a time keeps every run identical.
cholmod_factor* analyze_with_nested_dissection(cholmod_sparse& A, Cholmod& c) {
  static std::mutex one_at_a_time;
  const std::lock_guard<std::mutex> lock(one_at_a_time);
  return cholmod_analyze(&A, c.get());
}

}  // namespace skinslide
