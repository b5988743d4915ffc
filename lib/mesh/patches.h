// Patches: the selected faces split into edge-connected components, checked and with their loops.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/types.h"
#include "mesh/poly_mesh.h"

namespace skinslide {

/// One connected component of a selection: faces connected through shared edges (faces that touch
/// only at a vertex are separate components, and such a vertex stays fixed in both).
struct PatchComponent {
  Index selection = 0;                    ///< which selection (--patch file) it came from
  std::vector<Index> faces;               ///< mesh face ids, ascending
  std::vector<Index> vertices;            ///< mesh vertex ids, ascending
  std::vector<std::vector<Index>> loops;  ///< boundary loops (mesh ids), see boundary_loops()
};

/// Names a face in messages, e.g. "face 57 (bind.obj:301)".
using FaceNamer = std::function<std::string(Index face)>;

/// Names a selection in messages, e.g. "--patch left.txt"; by default "patch 0", "patch 1", ...
using SelectionNamer = std::function<std::string(Index selection)>;

/// Splits each selection (ascending face ids of `mesh`) into components, ordered by smallest
/// vertex id (then smallest face id).
/// \throw Error(Input) naming the culprit for: a face in two selections (both named), a face
///        with a repeated vertex, an edge in more than two selected faces, two faces traversing
///        an edge the same way (inconsistent orientation; non-orientable patch), a vertex whose
///        faces form several fans (bow-tie), a vertex interior to one component and touched by
///        another, and a component with no boundary (closed surface).
std::vector<PatchComponent> patch_components(const PolyMesh& mesh,
                                             const std::vector<std::vector<Index>>& selections,
                                             const FaceNamer& name_face,
                                             const SelectionNamer& name_selection = {});

}  // namespace skinslide
