// Boundary loops through OpenMesh's halfedge structure (the only OpenMesh user).
#pragma once

#include <vector>

#include "core/types.h"
#include "mesh/poly_mesh.h"

namespace skinslide {

/// The boundary loops of the surface made of `faces` of `mesh` (mesh vertex ids). Each loop starts
/// at its smallest vertex id and walks in the direction its face traverses the boundary edge.
/// Loops are ordered by their start vertex.
/// \pre the faces form an edge-manifold, consistently oriented surface whose vertices each have
///      one fan of faces (mesh/patches.h checks this first, with messages for the user).
/// \throw Error(Internal) when OpenMesh refuses a face despite those checks.
std::vector<std::vector<Index>> boundary_loops(const PolyMesh& mesh,
                                               const std::vector<Index>& faces);

}  // namespace skinslide
