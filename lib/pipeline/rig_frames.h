// A rigged, animated glTF character as the frame source: the bind is the mesh as stored, each
// frame the mesh posed (morph targets, then the skin or the mesh node's transform) at one sampled
// time of one clip (pose/animation.h, pose/skinning.h).
#pragma once

#include <string>
#include <vector>

#include "io/mesh_file.h"
#include "pose/rig.h"

namespace skinslide {

struct RigOptions {
  std::string animation;  ///< clip name or index; empty = the only clip
  double fps = 0;         ///< sample every 1/fps s from the clip's start to its end; 0 = key times
};

/// What is computed once per character: the rig, the chosen clip and its sample times.
struct RigClip {
  Rig rig;
  Index animation = 0;
  std::vector<double> times;       ///< seconds, ascending
  std::vector<std::string> names;  ///< "<character stem>.<frame>", the frame number zero-padded
                                   ///< to 4 digits (more when needed), counted from 0
};

/// The rig and sample times of `character` (read by read_gltf_file).
/// \throw Error(Input) when nothing poses its mesh (gltf_rig); Error(Usage) when the clip does
///        not exist.
RigClip rig_clip(const MeshFile& character, const RigOptions& options);

/// Frame `k` of the clip: `character` posed at times[k] (morph targets, then linear blend
/// skinning or the mesh node's transform), expressed in the mesh node's space at rest
/// (pose/skinning.h node_space_pose_at), as a static glTF document (io/gltf/gltf.h posed_gltf_file)
/// whose `mesh` has the bind's faces. Pure: frames may be made in parallel.
MeshFile rig_frame(const MeshFile& character, const RigClip& clip, std::size_t k);

}  // namespace skinslide
