// CHOLMOD (SuiteSparse), set up one way for the whole program: the paper method's frame nets and
// the elastic method's bind-time factors order and factorise through here, and only solve/ and
// paper/bar_net.cpp include it.
#pragma once

#include <cholmod.h>

#include "core/types.h"

namespace skinslide {

/// CHOLMOD's workspace with the settings shared by the analysis and every factorisation: one
/// fixed ordering, so the factor never depends on which ordering a heuristic happened to prefer:
/// CHOLMOD's nested dissection (METIS bisections, constrained minimum degree on the parts), the
/// fastest frame factors of the orderings measured; simplicial LDL^T, which beat the supernodal
/// factor (tests/bench/README.md "Performance"); silent.
class Cholmod {
 public:
  Cholmod();
  ~Cholmod();
  Cholmod(const Cholmod&) = delete;
  Cholmod& operator=(const Cholmod&) = delete;
  cholmod_common* operator->() { return &c_; }
  cholmod_common* get() { return &c_; }

 private:
  cholmod_common c_;
};

/// A view of a symmetric matrix of `size` rows in compressed columns (`start`, `index`,
/// `value`; both triangles stored, CHOLMOD reads the lower one). No copy.
cholmod_sparse cholmod_view(Index size, const Index* start, const Index* index,
                            const double* value);

/// The same view of K.
cholmod_sparse cholmod_view(const SparseMatrix& K);

/// The symbolic analysis of A with the nested-dissection ordering, one at a time (see .cpp).
cholmod_factor* analyze_with_nested_dissection(cholmod_sparse& A, Cholmod& c);

}  // namespace skinslide
