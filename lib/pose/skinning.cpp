#include "pose/skinning.h"

#include <cmath>
#include <string>

#include <Eigen/LU>

#include "core/check.h"
#include "core/error.h"
#include "pose/animation.h"

namespace skinslide {

Mat4 local_matrix(const NodeTransform& x) {
  if (x.has_matrix) return x.matrix;
  Mat4 m = Mat4::Identity();
  m.topLeftCorner<3, 3>() = x.rotation.normalized().toRotationMatrix() * x.scale.asDiagonal();
  m.topRightCorner<3, 1>() = x.translation;
  return m;
}

std::vector<Mat4> world_matrices(const Rig& rig, const std::vector<NodeTransform>& local) {
  const std::size_t n = rig.nodes.size();
  SKINSLIDE_CHECK(local.size() == n, "one local transform per node");
  std::vector<Mat4> world(n);
  std::vector<char> done(n, 0);
  std::vector<Index> chain;
  for (std::size_t i = 0; i < n; ++i) {
    // Walk up to the first node already done (or a root), then come back down.
    chain.clear();
    for (Index j = static_cast<Index>(i); j >= 0 && !done[j]; j = rig.nodes[j].parent) {
      chain.push_back(j);
      SKINSLIDE_CHECK(chain.size() <= n, "node hierarchy has a cycle");
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const Index j = *it;
      const Index p = rig.nodes[j].parent;
      world[j] = p >= 0 ? Mat4(world[p] * local_matrix(local[j])) : local_matrix(local[j]);
      done[j] = 1;
    }
  }
  return world;
}

std::vector<Mat4> joint_matrices(const Skin& skin, const std::vector<Mat4>& world) {
  std::vector<Mat4> m(skin.joints.size());
  for (std::size_t j = 0; j < skin.joints.size(); ++j)
    m[j] = world[skin.joints[j]] * skin.inverse_bind[j];
  return m;
}

namespace {

Vec3 unit_or(const Vec3& v, const Vec3& fallback) {
  const double len = v.norm();
  return len > 0 && std::isfinite(len) ? Vec3(v / len) : fallback;
}

Pose skin(const Rig& rig, const Positions3& positions, const Positions3& normals,
          const std::vector<Mat4>& joint) {
  const Influences& inf = rig.influences;
  const Index n = static_cast<Index>(positions.size());
  SKINSLIDE_CHECK(rig.skinned(), "skinning a rig without a skin");
  SKINSLIDE_CHECK(inf.vertex_count() == n, "one influence list per vertex");
  SKINSLIDE_CHECK(normals.empty() || static_cast<Index>(normals.size()) == n,
                  "one normal per vertex");
  const bool with_normals = !normals.empty();
  Pose pose;
  pose.positions.resize(n);
  if (with_normals) pose.normals.resize(n);
  for (Index v = 0; v < n; ++v) {
    Mat4 m = Mat4::Zero();
    double total = 0;
    for (Index k = inf.start[v]; k < inf.start[v + 1]; ++k) {
      m += inf.weight[k] * joint[inf.joint[k]];
      total += inf.weight[k];
    }
    SKINSLIDE_CHECK(total > 0, "vertex without skin weight");
    m /= total;
    const Vec3 p = m.topLeftCorner<3, 3>() * positions[v] + m.topRightCorner<3, 1>();
    if (!p.allFinite())
      throw Error(ErrorKind::Numeric, "skinning: vertex " + std::to_string(v) + " is not finite");
    pose.positions[v] = p;
    if (with_normals) {
      const Eigen::Matrix3d a = m.topLeftCorner<3, 3>();
      pose.normals[v] = unit_or(a.inverse().transpose() * normals[v], normals[v]);
    }
  }
  return pose;
}

}  // namespace

Pose morphed_pose(const Rig& rig, const std::vector<double>& weights) {
  SKINSLIDE_CHECK(weights.size() == rig.targets.size(), "one morph weight per target");
  Pose pose;
  pose.positions = rig.bind_positions;
  pose.normals = rig.bind_normals;
  const std::size_t n = pose.positions.size();
  std::vector<char> normal_moved(pose.normals.size(), 0);
  for (std::size_t i = 0; i < weights.size(); ++i) {
    const double w = weights[i];
    if (w == 0) continue;  // so that a zero weight leaves the bind's bits alone
    const MorphTarget& m = rig.targets[i];
    SKINSLIDE_CHECK(m.position_vertex.size() == m.position_delta.size() &&
                        m.normal_vertex.size() == m.normal_delta.size(),
                    "morph target vertices and displacements differ in count");
    for (std::size_t k = 0; k < m.position_vertex.size(); ++k) {
      const auto v = static_cast<std::size_t>(m.position_vertex[k]);
      SKINSLIDE_CHECK(v < n, "morph target vertex out of range");
      pose.positions[v] += w * m.position_delta[k];
    }
    if (pose.normals.empty()) continue;
    for (std::size_t k = 0; k < m.normal_vertex.size(); ++k) {
      const auto v = static_cast<std::size_t>(m.normal_vertex[k]);
      SKINSLIDE_CHECK(v < n, "morph target vertex out of range");
      pose.normals[v] += w * m.normal_delta[k];
      normal_moved[v] = 1;
    }
  }
  for (std::size_t v = 0; v < n; ++v)
    if (!pose.positions[v].allFinite())
      throw Error(ErrorKind::Numeric,
                  "morph targets: vertex " + std::to_string(v) + " is not finite");
  for (std::size_t v = 0; v < normal_moved.size(); ++v)
    if (normal_moved[v]) pose.normals[v] = unit_or(pose.normals[v], rig.bind_normals[v]);
  return pose;
}

Pose skinned_pose(const Rig& rig, const Pose& rest, const std::vector<Mat4>& joint) {
  return skin(rig, rest.positions, rest.normals, joint);
}

Pose skinned_pose(const Rig& rig, const std::vector<Mat4>& joint) {
  return skin(rig, rig.bind_positions, rig.bind_normals, joint);
}

Pose transformed_pose(const Pose& pose, const Mat4& m) {
  const Eigen::Matrix3d a = m.topLeftCorner<3, 3>();
  const Eigen::Matrix3d n = a.inverse().transpose();
  Pose out;
  out.positions.reserve(pose.positions.size());
  for (const Vec3& p : pose.positions) {
    const Vec3 q = a * p + m.topRightCorner<3, 1>();
    if (!q.allFinite())
      throw Error(ErrorKind::Numeric, "node transform: vertex " +
                                          std::to_string(out.positions.size()) + " is not finite");
    out.positions.push_back(q);
  }
  out.normals.reserve(pose.normals.size());
  for (const Vec3& v : pose.normals) out.normals.push_back(unit_or(n * v, v));
  return out;
}

Pose to_node_space(const Pose& pose, const Mat4& node_world) {
  const Mat4 inv = node_world.inverse();
  const Eigen::Matrix3d a = node_world.topLeftCorner<3, 3>().transpose();
  Pose out;
  out.positions.reserve(pose.positions.size());
  for (const Vec3& p : pose.positions)
    out.positions.push_back(inv.topLeftCorner<3, 3>() * p + inv.topRightCorner<3, 1>());
  out.normals.reserve(pose.normals.size());
  for (const Vec3& n : pose.normals) {
    const Vec3 m = a * n;
    const double len = m.norm();
    out.normals.push_back(len > 0 && std::isfinite(len) ? Vec3(m / len) : n);
  }
  return out;
}

Pose pose_at(const Rig& rig, const Animation* animation, double t) {
  const std::vector<Mat4> world = world_matrices(rig, animated_transforms(rig, animation, t));
  if (rig.skinned() && rig.targets.empty())
    return skinned_pose(rig, joint_matrices(rig.skin, world));
  const Pose rest = morphed_pose(rig, animated_weights(rig, animation, t));
  if (rig.skinned()) return skinned_pose(rig, rest, joint_matrices(rig.skin, world));
  SKINSLIDE_CHECK(rig.mesh_node >= 0 && rig.mesh_node < static_cast<Index>(world.size()),
                  "an unskinned rig needs its mesh node");
  return transformed_pose(rest, world[rig.mesh_node]);
}

Pose node_space_pose_at(const Rig& rig, const Animation* animation, double t) {
  SKINSLIDE_CHECK(rig.mesh_node >= 0 && rig.mesh_node < static_cast<Index>(rig.nodes.size()),
                  "the rig's mesh node");
  const std::vector<Mat4> rest_world = world_matrices(rig, animated_transforms(rig, nullptr, 0));
  const Mat4& rest = rest_world[rig.mesh_node];
  if (rig.skinned()) return to_node_space(pose_at(rig, animation, t), rest);
  const std::vector<Mat4> world = world_matrices(rig, animated_transforms(rig, animation, t));
  Pose morphed = morphed_pose(rig, animated_weights(rig, animation, t));
  if (world[rig.mesh_node] == rest) return morphed;
  return transformed_pose(morphed, Mat4(rest.inverse() * world[rig.mesh_node]));
}

}  // namespace skinslide
