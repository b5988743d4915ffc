// A fresh OBJ from a PolyMesh: for frames that come from no OBJ file (a posed glTF character).
#pragma once

#include <string>

#include "core/types.h"
#include "mesh/poly_mesh.h"

namespace skinslide {

/// OBJ text of `mesh`'s faces with `positions` (#V): a comment line naming `source`, one `v` line
/// per vertex (shortest round-trip numbers), one `f` line per face (1-based), "\n" endings.
/// \pre positions.size() == mesh.vertex_count()
std::string obj_text(const PolyMesh& mesh, const Positions3& positions, const std::string& source);

}  // namespace skinslide
