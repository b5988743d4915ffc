// The rig of a glTF character (skin, node hierarchy, clips) as plain data for pose/.
#pragma once

#include <string>

#include "pose/rig.h"

namespace skinslide {

struct GltfDocument;  // io/gltf_document.h

/// The rig of the mesh read into `doc`: the skin of the first node (in node order) that
/// instantiates that mesh with a skin, the whole node hierarchy with its stored transforms, the
/// influences (JOINTS_n/WEIGHTS_n, every set) and the bind positions/normals of every raw vertex
/// (same numbering as GltfDocument::welded), and every animation's TRS channels.
/// Morph targets are not applied: the bind is the base POSITION.
/// \param path names the file in error messages
/// \throw Error(Input) when the mesh has no skin, a vertex has no positive weight, a joint index
///        is out of range, a node has two parents, an animated node has a matrix, or an
///        accessor is malformed.
Rig gltf_rig(const GltfDocument& doc, const std::string& path);

/// The clip named `want`, else the one at index `want`; empty `want` = the only clip.
/// \throw Error(Usage) listing the clips (index, name, duration) when there is no such clip, or
///        when `want` is empty and there are several.
Index find_animation(const Rig& rig, const std::string& want, const std::string& path);

}  // namespace skinslide
