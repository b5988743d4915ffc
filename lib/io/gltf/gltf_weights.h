// Slide weights stored in a glTF mesh as a vertex attribute (`--weights-from-gltf-attribute`).
#pragma once

#include <string>
#include <vector>

#include "io/mesh_file.h"

namespace skinslide {

/// Slide weights from the vertex attribute `name` (e.g. `_SLIDE_WEIGHT`) of the glTF mesh
/// `file` was read from: one per welded vertex, in [0, 1].
/// The attribute is a SCALAR accessor of floats, or of normalized unsigned bytes or shorts
/// (0..255 or 0..65535 read as 0..1); sparse accessors are read. Every triangle primitive of the
/// mesh (the surface io/gltf/gltf.h reads; points and lines primitives are ignored) must have it.
/// A welded vertex takes the weight of its first raw copy (the one its position comes from):
/// raw copies that disagree, as on a seam painted differently on each side, do not fail.
/// Output: #V weights (V = file.mesh.vertex_count()).
/// \throw Error(Usage) when `file` is not a glTF/GLB file.
/// \throw Error(Input) "path: mesh M primitive P: ..." naming the attribute, for a primitive
///        without it, an accessor that does not exist or is not of a type above, an element
///        count other than POSITION's, or an element outside [0, 1] or not finite.
std::vector<double> gltf_attribute_weights(const MeshFile& file, const std::string& name);

}  // namespace skinslide
