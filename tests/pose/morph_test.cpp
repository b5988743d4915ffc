// Morph targets and node transforms of unskinned meshes (pose/skinning.h), on hand-built rigs.
#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"
#include "pose/animation.h"
#include "pose/skinning.h"

namespace skinslide {
namespace {

// One unskinned node (node 0) holding three vertices, two targets.
Rig two_target_rig() {
  Rig rig;
  rig.nodes.resize(1);
  rig.mesh_node = 0;
  rig.bind_positions = {{0.1, 0.2, 0.3}, {1, 0, 0}, {0, 1, 0}};
  rig.bind_normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  rig.targets.resize(2);
  rig.targets[0].position_vertex = {0, 2};
  rig.targets[0].position_delta = {{0.7, 0, 0}, {0, 0, 3}};
  rig.targets[0].normal_vertex = {2};
  rig.targets[0].normal_delta = {{0, -1, 0}};
  rig.targets[1].position_vertex = {2};
  rig.targets[1].position_delta = {{0, 0, -1}};
  rig.weights = {0, 0};
  return rig;
}

TEST(Morph, ZeroWeightsLeaveTheBindBitForBit) {
  const Rig rig = two_target_rig();
  const Pose p = morphed_pose(rig, {0, 0});
  EXPECT_EQ(p.positions, rig.bind_positions);
  EXPECT_EQ(p.normals, rig.bind_normals);
}

TEST(Morph, WeightedSumOfTargetsAndRenormalisedNormals) {
  const Rig rig = two_target_rig();
  const Pose p = morphed_pose(rig, {0.5, 2});
  EXPECT_EQ(p.positions[0], Vec3(0.1 + 0.35, 0.2, 0.3));
  EXPECT_EQ(p.positions[1], Vec3(1, 0, 0));
  EXPECT_EQ(p.positions[2], Vec3(0, 1, 1.5 - 2));
  EXPECT_NEAR((p.normals[2] - Vec3(0, -0.5, 1).normalized()).norm(), 0, 1e-15);
  EXPECT_EQ(p.normals[0], Vec3(0, 0, 1));
  // A normal summing to zero keeps the stored one; a non-finite position is an error.
  EXPECT_EQ(morphed_pose(rig, {1, 0}).normals[2], Vec3(0, -1, 1).normalized());
  Rig flat = rig;
  flat.targets[0].normal_delta = {{0, 0, -1}};
  EXPECT_EQ(morphed_pose(flat, {1, 0}).normals[2], Vec3(0, 0, 1));
  EXPECT_THROW(morphed_pose(rig, {INFINITY, 0}), Error);
}

TEST(Morph, UnskinnedMeshIsPlacedByItsNodeAndNormalsByTheInverseTranspose) {
  Rig rig = two_target_rig();
  rig.nodes[0].rest.scale = Vec3(2, 1, 1);
  rig.nodes[0].rest.translation = Vec3(0, 0, 5);
  Animation a;
  AnimationChannel c;
  c.node = 0;
  c.path = ChannelPath::Weights;
  c.sampler.width = 2;
  c.sampler.times = {0, 1};
  c.sampler.values = {0, 0, 1, 0};
  a.channels = {c};
  a.end = 1;
  // World space: scaled by (2,1,1), raised by 5; the normal (0,-1,1)/sqrt2 at weight 1 becomes
  // (0,-1,1) under the inverse transpose diag(1/2, 1, 1): unchanged direction.
  const Pose w = pose_at(rig, &a, 1);
  EXPECT_NEAR((w.positions[0] - Vec3(1.6, 0.2, 5.3)).norm(), 0, 1e-15);
  EXPECT_NEAR((w.normals[2] - Vec3(0, -1, 1).normalized()).norm(), 0, 1e-15);
  // In the node's rest space (not animated): the morphed bind itself.
  EXPECT_EQ(node_space_pose_at(rig, &a, 1).positions, morphed_pose(rig, {1, 0}).positions);
  // A tilted normal under a non-uniform scale: (1,0,1) -> diag(1/2,1,1) (1,0,1), renormalised.
  Pose tilted;
  tilted.positions = {{0, 0, 0}};
  tilted.normals = {Vec3(1, 0, 1).normalized()};
  Mat4 m = Mat4::Identity();
  m(0, 0) = 2;
  EXPECT_NEAR((transformed_pose(tilted, m).normals[0] - Vec3(0.5, 0, 1).normalized()).norm(), 0,
              1e-15);
}

}  // namespace
}  // namespace skinslide
