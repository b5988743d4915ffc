// Linear blend skinning of a Rig: node world matrices, joint matrices, posed vertices.
// glTF 2.0 section 3.7.3 (skins): a skinned mesh ignores its own node's transform; joint j moves
// a vertex by world(joint j) * inverse_bind[j].
#pragma once

#include <vector>

#include "pose/rig.h"

namespace skinslide {

/// The 4x4 matrix of a local transform: `matrix`, or T * R * S.
Mat4 local_matrix(const NodeTransform& x);

/// World matrix of every node (#nodes): the product of local matrices from its root down.
/// \pre local.size() == rig.nodes.size(); the parent links form a forest (checked on reading).
std::vector<Mat4> world_matrices(const Rig& rig, const std::vector<NodeTransform>& local);

/// Skinning matrix of every joint (#joints): world(joints[j]) * inverse_bind[j].
std::vector<Mat4> joint_matrices(const Skin& skin, const std::vector<Mat4>& world);

/// A posed mesh: raw vertex positions, and normals when the rig has bind normals.
struct Pose {
  Positions3 positions;  ///< #raw vertices, in the joints' world space
  Positions3 normals;    ///< #raw vertices (unit) or empty
};

/// Linear blend skinning: p' = sum_k w_k M_k p / sum_k w_k over each vertex's influences (so
/// weights that do not add up to 1 are normalised); normals by the inverse transpose of the
/// blended 3x3, renormalised.
/// \throw Error(Numeric) when a result is not finite.
Pose skinned_pose(const Rig& rig, const std::vector<Mat4>& joint);

/// `pose` (in the joints' world space) expressed in the space of a node whose world matrix is
/// `node_world`: positions by its inverse, normals by its transpose (renormalised). Skinning
/// ignores the mesh node's transform; this undoes the one a viewer applies to an unskinned copy.
Pose to_node_space(const Pose& pose, const Mat4& node_world);

/// The character at time `t` of `animation` (null = the rest pose: the nodes' stored transforms).
Pose pose_at(const Rig& rig, const Animation* animation, double t);

}  // namespace skinslide
