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

Pose skinned_pose(const Rig& rig, const std::vector<Mat4>& joint) {
  const Influences& inf = rig.influences;
  const Index n = static_cast<Index>(rig.bind_positions.size());
  SKINSLIDE_CHECK(inf.vertex_count() == n, "one influence list per vertex");
  const bool normals = !rig.bind_normals.empty();
  Pose pose;
  pose.positions.resize(n);
  if (normals) pose.normals.resize(n);
  for (Index v = 0; v < n; ++v) {
    Mat4 m = Mat4::Zero();
    double total = 0;
    for (Index k = inf.start[v]; k < inf.start[v + 1]; ++k) {
      m += inf.weight[k] * joint[inf.joint[k]];
      total += inf.weight[k];
    }
    SKINSLIDE_CHECK(total > 0, "vertex without skin weight");
    m /= total;
    const Vec3 p = m.topLeftCorner<3, 3>() * rig.bind_positions[v] + m.topRightCorner<3, 1>();
    if (!p.allFinite())
      throw Error(ErrorKind::Numeric, "skinning: vertex " + std::to_string(v) + " is not finite");
    pose.positions[v] = p;
    if (normals) {
      const Eigen::Matrix3d a = m.topLeftCorner<3, 3>();
      Vec3 nv = a.inverse().transpose() * rig.bind_normals[v];
      const double len = nv.norm();
      pose.normals[v] = len > 0 && std::isfinite(len) ? Vec3(nv / len) : rig.bind_normals[v];
    }
  }
  return pose;
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
  return skinned_pose(rig, joint_matrices(rig.skin, world));
}

}  // namespace skinslide
