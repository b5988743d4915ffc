// Posing a Rig: morph targets, then linear blend skinning (node world matrices, joint matrices)
// or, for an unskinned mesh, its node's world matrix. glTF 2.0 section 3.7.2.2 (morph targets:
// applied first) and 3.7.3 (skins): a skinned mesh ignores its own node's transform; joint j
// moves a vertex by world(joint j) * inverse_bind[j].
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

/// The bind with morph weights `weights` (#targets) applied: POSITION + sum_i w_i * target_i
/// POSITION; normals NORMAL + sum_i w_i * target_i NORMAL, renormalised (a zero sum keeps the
/// stored normal). Positions come back bit-identical to the bind where no target moves them or
/// all weights are 0.
/// \throw Error(Numeric) when a result is not finite.
Pose morphed_pose(const Rig& rig, const std::vector<double>& weights);

/// Linear blend skinning of `rest` (the bind, or morphed_pose): p' = sum_k w_k M_k p / sum_k w_k
/// over each vertex's influences (so weights that do not add up to 1 are normalised); normals by
/// the inverse transpose of the blended 3x3, renormalised.
/// \pre rig.skinned()
/// \throw Error(Numeric) when a result is not finite.
Pose skinned_pose(const Rig& rig, const Pose& rest, const std::vector<Mat4>& joint);

/// skinned_pose of the bind (no morph).
Pose skinned_pose(const Rig& rig, const std::vector<Mat4>& joint);

/// `pose` mapped by `m`: positions by it, normals by the inverse transpose of its 3x3,
/// renormalised.
Pose transformed_pose(const Pose& pose, const Mat4& m);

/// `pose` (in the joints' world space) expressed in the space of a node whose world matrix is
/// `node_world`: positions by its inverse, normals by its transpose (renormalised). Skinning
/// ignores the mesh node's transform; this undoes the one a viewer applies to an unskinned copy.
Pose to_node_space(const Pose& pose, const Mat4& node_world);

/// The character at time `t` of `animation` (null = the rest pose: the nodes' stored transforms
/// and rig.weights), in world space: morphed by the animated weights, then skinned, or (an
/// unskinned mesh) placed by the mesh node's animated world matrix.
Pose pose_at(const Rig& rig, const Animation* animation, double t);

/// pose_at expressed in the mesh node's space at rest (to_node_space with the node's world
/// matrix at the nodes' stored transforms): what a static copy shown through that node needs.
/// For an unskinned mesh this is the morphed bind mapped by rest_world^-1 * world(t), and the
/// morphed bind itself, bit for bit, when the node's world matrix is not animated.
Pose node_space_pose_at(const Rig& rig, const Animation* animation, double t);

}  // namespace skinslide
