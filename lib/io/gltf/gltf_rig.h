// The rig of a glTF character (skin, node hierarchy, clips) as plain data for pose/.
#pragma once

#include <string>

#include "pose/rig.h"

namespace skinslide {

struct GltfDocument;  // io/gltf/gltf_document.h

/// The rig of the mesh read into `doc`: its node (the first, in node order, that instantiates it
/// with a skin, else the first that instantiates it), that node's skin if any, the whole node
/// hierarchy with its stored transforms, the influences (JOINTS_n/WEIGHTS_n, every set; skinned
/// meshes only), the bind positions/normals of every raw vertex (same numbering as
/// GltfDocument::welded), the morph targets (POSITION and NORMAL displacements) with their
/// default weights (the node's `weights`, else the mesh's, else zeros), and every animation's
/// TRS channels and the mesh node's weights channel. The bind is the base POSITION.
/// \param path names the file in error messages
/// \throw Error(Input) when nothing poses the mesh (no skin, no morph targets, and no animation
///        of its node or a node above it), or morph targets without a node; when a vertex has no
///        positive weight, a joint index is out of range, a node has two parents, an animated
///        node has a matrix, primitives differ in their number of morph targets, weights or a
///        weights sampler do not match that number, or an accessor is malformed.
Rig gltf_rig(const GltfDocument& doc, const std::string& path);

/// The clip named `want`, else the one at index `want`; empty `want` = the only clip.
/// \throw Error(Usage) listing the clips (index, name, duration) when there is no such clip, or
///        when `want` is empty and there are several.
Index find_animation(const Rig& rig, const std::string& want, const std::string& path);

}  // namespace skinslide
