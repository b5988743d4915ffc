// An animated character as plain data: node hierarchy, one skin (or none), per-vertex influences,
// morph targets and animation clips. Filled from glTF by io/gltf/gltf_rig.h; posed by
// pose/animation.h and pose/skinning.h. Conventions are glTF 2.0's (section 3.7.2.2 morph
// targets, 3.7.3 skins, 3.11 animations).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/types.h"

namespace skinslide {

using Mat4 = Eigen::Matrix4d;
using Quat = Eigen::Quaterniond;

/// A node's local transform: a matrix, or translation * rotation * scale (TRS).
struct NodeTransform {
  bool has_matrix = false;
  Mat4 matrix = Mat4::Identity();  ///< used when has_matrix
  Vec3 translation = Vec3::Zero();
  Quat rotation = Quat::Identity();  ///< unit quaternion
  Vec3 scale = Vec3::Ones();
};

struct RigNode {
  std::string name;
  Index parent = -1;   ///< -1 for a root; parents may come after children in the array
  NodeTransform rest;  ///< the transform stored in the file (the pose without animation)
};

/// Joint j's skinning matrix is world(joints[j]) * inverse_bind[j] (the mesh node's own
/// transform is ignored, glTF 2.0 section 3.7.3.3).
struct Skin {
  std::vector<Index> joints;       ///< node ids
  std::vector<Mat4> inverse_bind;  ///< one per joint (identity when the file has none)
};

/// Up to 4 * n influences of each vertex (JOINTS_n/WEIGHTS_n), CSR: vertex v has
/// joint[start[v] .. start[v+1]) (indices into Skin::joints) with weight[...] (> 0, as stored).
struct Influences {
  std::vector<Index> start{0};
  std::vector<Index> joint;
  std::vector<double> weight;
  Index vertex_count() const { return static_cast<Index>(start.size()) - 1; }
};

enum class Interpolation { Step, Linear, CubicSpline };
enum class ChannelPath { Translation, Rotation, Scale, Weights };

/// One animation sampler with its keys. `values` holds `width` doubles per key (3 for
/// translation/scale, 4 for rotation as x, y, z, w, one per morph target for weights);
/// CUBICSPLINE holds 3 per key (in-tangent, value, out-tangent), as glTF stores them.
struct AnimationSampler {
  Interpolation interpolation = Interpolation::Linear;
  std::vector<double> times;   ///< seconds, strictly increasing
  std::vector<double> values;  ///< #keys (x3 for CUBICSPLINE) x width
  int width = 3;
};

/// A Weights channel always targets Rig::mesh_node (channels animating other nodes' weights do
/// not move the mesh and are not kept).
struct AnimationChannel {
  Index node = -1;
  ChannelPath path = ChannelPath::Translation;
  AnimationSampler sampler;
};

struct Animation {
  std::string name;  ///< may be empty (three of the four shared characters have no names)
  std::vector<AnimationChannel> channels;  ///< TRS of any node; weights of the mesh node only
  double start = 0;                        ///< earliest key time over all channels
  double end = 0;                          ///< latest key time
};

/// One morph target: the displacements it adds, per unit weight, to the raw vertices it moves
/// (those with a non-zero displacement; ascending raw ids). A target without POSITION (or
/// NORMAL) in a primitive moves none of that primitive's vertices (or normals).
struct MorphTarget {
  std::vector<Index> position_vertex;
  Positions3 position_delta;
  std::vector<Index> normal_vertex;
  Positions3 normal_delta;  ///< used only when Rig::bind_normals is not empty
};

/// Everything needed to pose the character's vertices.
struct Rig {
  std::vector<RigNode> nodes;
  /// The node that instantiates the mesh: the first (in node order) giving it a skin, else the
  /// first instantiating it.
  Index mesh_node = -1;
  Skin skin;                         ///< no joints: the mesh is not skinned (see skinned())
  Influences influences;             ///< one entry per raw vertex when skinned, else none
  Positions3 bind_positions;         ///< raw vertex positions as stored (the bind pose)
  Positions3 bind_normals;           ///< raw normals as stored; empty when the mesh has none
  std::vector<MorphTarget> targets;  ///< the mesh's morph targets, in glTF order
  /// Morph weights without animation (#targets): the mesh node's `weights`, else the mesh's,
  /// else zeros.
  std::vector<double> weights;
  std::vector<Animation> animations;

  /// Skinned meshes ignore their node's transform; unskinned ones are placed by it.
  bool skinned() const { return !skin.joints.empty(); }
};

}  // namespace skinslide
