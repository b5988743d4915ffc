#include "pose/skinning.h"

#include <cmath>

#include <gtest/gtest.h>

#include "pose/animation.h"

namespace skinslide {
namespace {

// Two joints: joint 0 at the origin (identity), joint 1 at (1,0,0) turned 90 degrees about z by
// the animation, its inverse bind matrix a translation by (-1,0,0). Node 1 is stored before its
// parent (node 2, the root) to check the hierarchy does not depend on node order.
Rig two_joint_rig() {
  Rig rig;
  rig.nodes.resize(3);
  rig.nodes[0].parent = 2;  // joint 0
  rig.nodes[1].parent = 0;  // joint 1
  rig.nodes[1].rest.translation = Vec3(1, 0, 0);
  rig.skin.joints = {0, 1};
  Mat4 ibm1 = Mat4::Identity();
  ibm1(0, 3) = -1;
  rig.skin.inverse_bind = {Mat4::Identity(), ibm1};
  rig.bind_positions = {Vec3(2, 0, 0), Vec3(0.5, 0, 0)};
  rig.bind_normals = {Vec3(1, 0, 0), Vec3(0, 1, 0)};
  // Vertex 0: weights 1 and 1 (normalised to 0.5 each); vertex 1: joint 0 only.
  rig.influences.start = {0, 2, 3};
  rig.influences.joint = {0, 1, 0};
  rig.influences.weight = {1, 1, 0.7};
  Animation a;
  AnimationChannel c;
  c.node = 1;
  c.path = ChannelPath::Rotation;
  c.sampler.width = 4;
  c.sampler.times = {0, 1};
  const double h = std::sqrt(0.5);
  c.sampler.values = {0, 0, 0, 1, 0, 0, h, h};  // identity, then 90 degrees about z
  a.channels = {c};
  a.end = 1;
  rig.animations = {a};
  return rig;
}

TEST(Skinning, RestPoseWithMatchingInverseBindsIsTheBind) {
  const Rig rig = two_joint_rig();
  const Pose p = pose_at(rig, nullptr, 0);
  EXPECT_NEAR((p.positions[0] - Vec3(2, 0, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((p.normals[0] - Vec3(1, 0, 0)).norm(), 0, 1e-15);
}

TEST(Skinning, HandComputedBlendOfTwoJoints) {
  const Rig rig = two_joint_rig();
  const Pose p = pose_at(rig, &rig.animations[0], 1.0);
  // Joint 1 takes (2,0,0) to (1,0,0) + R90 (1,0,0) = (1,1,0); joint 0 leaves it: the mean is
  // (1.5, 0.5, 0). The blended 3x3 is (I + R90) / 2 = R45 / sqrt(2): normals turn by 45 degrees.
  EXPECT_NEAR((p.positions[0] - Vec3(1.5, 0.5, 0)).norm(), 0, 1e-15);
  const double h = std::sqrt(0.5);
  EXPECT_NEAR((p.normals[0] - Vec3(h, h, 0)).norm(), 0, 1e-15);
  // A single influence with weight 0.7 is normalised to 1.
  EXPECT_NEAR((p.positions[1] - Vec3(0.5, 0, 0)).norm(), 0, 1e-15);
  // Halfway, slerp gives 45 degrees: (1,0,0) + R45 (1,0,0) blended with (2,0,0).
  const Pose half = pose_at(rig, &rig.animations[0], 0.5);
  EXPECT_NEAR((half.positions[0] - Vec3((1 + h + 2) / 2, h / 2, 0)).norm(), 0, 1e-15);
}

TEST(Skinning, WorldMatricesComposeFromTheRootWhateverTheNodeOrder) {
  Rig rig = two_joint_rig();
  rig.nodes[2].rest.has_matrix = true;
  rig.nodes[2].rest.matrix = Mat4::Identity();
  rig.nodes[2].rest.matrix(2, 3) = 5;  // the root lifts everything by 5 in z
  const std::vector<Mat4> w = world_matrices(rig, animated_transforms(rig, nullptr, 0));
  EXPECT_EQ(Vec3(w[1].topRightCorner<3, 1>()), Vec3(1, 0, 5));
  EXPECT_EQ(Vec3(w[0].topRightCorner<3, 1>()), Vec3(0, 0, 5));
  // to_node_space undoes a node's world matrix: positions by its inverse.
  Pose p;
  p.positions = {Vec3(1, 2, 8)};
  p.normals = {Vec3(0, 0, 1)};
  const Pose local = to_node_space(p, w[2]);
  EXPECT_EQ(local.positions[0], Vec3(1, 2, 3));
  EXPECT_EQ(local.normals[0], Vec3(0, 0, 1));
}

TEST(Skinning, LocalMatrixIsTranslationRotationScale) {
  NodeTransform x;
  x.translation = Vec3(1, 2, 3);
  x.rotation = Quat(std::sqrt(0.5), 0, 0, std::sqrt(0.5));  // 90 degrees about z
  x.scale = Vec3(2, 3, 4);
  const Mat4 m = local_matrix(x);
  // (1,0,0) scaled to (2,0,0), turned to (0,2,0), moved to (1,4,3).
  EXPECT_NEAR((m * Eigen::Vector4d(1, 0, 0, 1) - Eigen::Vector4d(1, 4, 3, 1)).norm(), 0, 1e-14);
  // (0,1,0) scaled to (0,3,0), turned to (-3,0,0), moved to (-2,2,3).
  EXPECT_NEAR((m * Eigen::Vector4d(0, 1, 0, 1) - Eigen::Vector4d(-2, 2, 3, 1)).norm(), 0, 1e-14);
}

}  // namespace
}  // namespace skinslide
