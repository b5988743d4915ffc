#include "solve/cholmod.h"

#include <mutex>

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

cholmod_sparse cholmod_view(const SparseMatrix& K) {
  cholmod_sparse A{};
  A.nrow = A.ncol = static_cast<size_t>(K.rows());
  A.nzmax = static_cast<size_t>(K.nonZeros());
  A.p = const_cast<Index*>(K.outerIndexPtr());
  A.i = const_cast<Index*>(K.innerIndexPtr());
  A.x = const_cast<double*>(K.valuePtr());
  A.stype = -1;
  A.itype = CHOLMOD_INT;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  return A;
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
