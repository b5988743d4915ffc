// Morph targets with --animation: hand-made files (tests/io/gltf/gltf_morph/, their contents listed
// in make.py there) read by io/gltf/gltf_rig and posed by pose/, each expected pose worked out by
// hand from glTF 2.0 sections 3.7.2.2 (morph targets), 3.11 and Appendix C (interpolation).
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "core/error.h"
#include "io/gltf/gltf.h"
#include "io/gltf/gltf_document.h"
#include "io/gltf/gltf_rig.h"
#include "io/gltf/gltf_test_util.h"
#include "pipeline/rig_frames.h"
#include "pose/animation.h"
#include "pose/skinning.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;
using testing::temp_dir;

std::string morph_file(const std::string& name) {
  return SKINSLIDE_SOURCE_DIR "/tests/io/gltf/gltf_morph/" + name;
}

Vec3 unit(double x, double y, double z) { return Vec3(x, y, z).normalized(); }

// Raw vertices of morph_quads.gltf with weights (w0, w1), in the mesh node's space: primitive 0
// (4 vertices) then primitive 1 (3); the POINTS primitive is not part of the surface.
Positions3 quads_at(double w0, double w1) {
  return {{0, 0, 0},      {1, 0, w0}, {1, 1 + w1, w0}, {0, 1 + w1, 0},
          {2, 0, 2 * w0}, {3, 0, w0}, {2, 1, 0.5 + w0}};
}
// Normals: primitive 0 NORMAL (0,0,1) + w0 (-1,0,0); primitive 1 (0,0,1) + w1 (0,1,0).
Positions3 quad_normals_at(double w0, double w1) {
  const Vec3 a = unit(-w0, 0, 1), b = unit(0, w1, 1);
  return {a, a, a, a, b, b, b};
}

Positions3 shifted(Positions3 p, const Vec3& by) {
  for (Vec3& x : p) x += by;
  return p;
}

double worst(const Positions3& a, const Positions3& b) {
  EXPECT_EQ(a.size(), b.size());
  double w = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) w = std::max(w, (a[i] - b[i]).norm());
  return w;
}

const Animation& clip(const Rig& rig, const std::string& name) {
  return rig.animations[find_animation(rig, name, "test")];
}

TEST(GltfMorph, ReadsTargetsWeightsAndTheMeshNodesWeightChannels) {
  const MeshFile f = read_gltf_file(morph_file("morph_quads.gltf"), {});
  const Rig rig = gltf_rig(*f.gltf, f.path);
  EXPECT_FALSE(rig.skinned());
  EXPECT_EQ(rig.mesh_node, 1);
  EXPECT_EQ(rig.bind_positions, quads_at(0, 0));  // the base POSITION, sparse substitution in
  ASSERT_EQ(rig.targets.size(), 2u);
  EXPECT_EQ(rig.weights, (std::vector<double>{0.25, 0.75}));  // the node's, not the mesh's
  // Only the vertices a target moves are kept: zeros of a dense accessor are dropped.
  EXPECT_EQ(rig.targets[0].position_vertex, (std::vector<Index>{1, 2, 4, 5, 6}));
  EXPECT_EQ(rig.targets[0].position_delta,
            (Positions3{{0, 0, 1}, {0, 0, 1}, {0, 0, 2}, {0, 0, 1}, {0, 0, 1}}));
  EXPECT_EQ(rig.targets[0].normal_vertex, (std::vector<Index>{0, 1, 2, 3}));
  EXPECT_EQ(rig.targets[1].position_vertex, (std::vector<Index>{2, 3}));
  EXPECT_EQ(rig.targets[1].normal_vertex, (std::vector<Index>{4, 5, 6}));
  ASSERT_EQ(rig.animations.size(), 3u);
  // "cubic": node 2's weights channel (keys to t = 3) does not move node 1's instance.
  const Animation& cubic = clip(rig, "cubic");
  ASSERT_EQ(cubic.channels.size(), 2u);
  EXPECT_EQ(cubic.channels[0].path, ChannelPath::Weights);
  EXPECT_EQ(cubic.channels[0].node, 1);
  EXPECT_EQ(cubic.channels[0].sampler.width, 2);
  EXPECT_EQ(cubic.end, 2);
  EXPECT_EQ(keyframe_times(cubic), (std::vector<double>{0, 1.5, 2}));
}

TEST(GltfMorph, WeightsAreSampledStepCubicSplineAndDefaultAsTheSpecSays) {
  const MeshFile f = read_gltf_file(morph_file("morph_quads.gltf"), {});
  const Rig rig = gltf_rig(*f.gltf, f.path);
  using W = std::vector<double>;
  const Animation& step = clip(rig, "step");
  EXPECT_EQ(animated_weights(rig, &step, -1), (W{0, 0}));  // before the first key: the first
  EXPECT_EQ(animated_weights(rig, &step, 0.5), (W{0, 0}));
  EXPECT_EQ(animated_weights(rig, &step, 1), (W{1, 0}));
  EXPECT_EQ(animated_weights(rig, &step, 1.999), (W{1, 0}));
  EXPECT_EQ(animated_weights(rig, &step, 2), (W{0, 1}));
  EXPECT_EQ(animated_weights(rig, &step, 9), (W{0, 1}));
  // CUBICSPLINE, keys at 0 and 2 (interval 2): v0 = (0,0), out0 = (1,0), v1 = (1,1),
  // in1 = (0,-1). At s = 1/2 the Hermite basis is (1/2, 1/8, 1/2, -1/8):
  // 2 * 1/8 * (1,0) + 1/2 * (1,1) - 2 * 1/8 * (0,-1) = (0.75, 0.75).
  // At s = 1/4: (27/32, 9/64, 5/32, -3/64): 9/32 (1,0) + 5/32 (1,1) + 3/32 (0,1) = (7/16, 1/4).
  const Animation& cubic = clip(rig, "cubic");
  const W mid = animated_weights(rig, &cubic, 1), quarter = animated_weights(rig, &cubic, 0.5);
  EXPECT_NEAR(mid[0], 0.75, 1e-15);
  EXPECT_NEAR(mid[1], 0.75, 1e-15);
  EXPECT_NEAR(quarter[0], 7.0 / 16, 1e-15);
  EXPECT_NEAR(quarter[1], 0.25, 1e-15);
  EXPECT_EQ(animated_weights(rig, &cubic, 2), (W{1, 1}));
  // A clip without a weights channel, and the rest: the node's weights.
  EXPECT_EQ(animated_weights(rig, &clip(rig, "move"), 0.5), (W{0.25, 0.75}));
  EXPECT_EQ(animated_weights(rig, nullptr, 0), (W{0.25, 0.75}));
}

TEST(GltfMorph, UnskinnedFramesAreTheMorphedBaseMovedByTheNodesAnimation) {
  const MeshFile f = read_gltf_file(morph_file("morph_quads.gltf"), {});
  const Rig rig = gltf_rig(*f.gltf, f.path);
  // Weight 1 on target 0 (STEP at its key): exact, and the normals of target 1 (weight 0) stay.
  Pose p = node_space_pose_at(rig, &clip(rig, "step"), 1);
  EXPECT_EQ(p.positions, quads_at(1, 0));
  EXPECT_LT(worst(p.normals, quad_normals_at(1, 0)), 1e-15);
  p = node_space_pose_at(rig, &clip(rig, "step"), 2);
  EXPECT_EQ(p.positions, quads_at(0, 1));
  // CUBICSPLINE mid-way: (0.75, 0.75); the root's STEP translation is still its rest value, so
  // the node's world matrix is its rest one and the frame is the morphed base, bit for bit.
  p = node_space_pose_at(rig, &clip(rig, "cubic"), 1);
  EXPECT_LT(worst(p.positions, quads_at(0.75, 0.75)), 1e-15);
  EXPECT_LT(worst(p.normals, quad_normals_at(0.75, 0.75)), 1e-15);
  // At t = 2 the root is 10 higher: in the mesh node's rest space the frame is 10 higher (the
  // node's rotation about z leaves z alone).
  p = node_space_pose_at(rig, &clip(rig, "cubic"), 2);
  EXPECT_LT(worst(p.positions, shifted(quads_at(1, 1), {0, 0, 10})), 1e-12);
  EXPECT_LT(worst(p.normals, quad_normals_at(1, 1)), 1e-15);
  // "move": the node's translation goes from (5,0,0) to (6,0,0) at t = 0.5; in its rest space
  // (turned 90 degrees about z) that is (0,-1,0). Weights: the node's default (0.25, 0.75).
  p = node_space_pose_at(rig, &clip(rig, "move"), 0.5);
  EXPECT_LT(worst(p.positions, shifted(quads_at(0.25, 0.75), {0, -1, 0})), 1e-12);
  EXPECT_LT(worst(p.normals, quad_normals_at(0.25, 0.75)), 1e-12);
  // In world space: root (0,0,10), node (6,0,0) and 90 degrees about z: (x,y,z) -> (6-y, x, 10+z).
  const Pose w = pose_at(rig, &clip(rig, "move"), 0.5);
  EXPECT_LT((w.positions[2] - Vec3(6 - 1.75, 1, 10.25)).norm(), 1e-12);
  EXPECT_LT((w.normals[0] - Vec3(0, -0.25, 1).normalized()).norm(), 1e-12);
}

TEST(GltfMorph, SkinnedMeshIsMorphedFirstThenSkinned) {
  const MeshFile f = read_gltf_file(morph_file("skinned_morph.gltf"), {});
  const Rig rig = gltf_rig(*f.gltf, f.path);
  EXPECT_TRUE(rig.skinned());
  ASSERT_EQ(rig.targets.size(), 1u);
  EXPECT_EQ(rig.weights, std::vector<double>{0});
  const Animation& bend = rig.animations[0];
  // t = 1: weight 1, knee turned 90 degrees about z about (0,1,0): (x,y,z) -> (1-y, x+1, z).
  // v2 = (1,2,0) + (1,0,0) = (2,2,0) -> (-1,3,0) (skinning before morphing would give (0,2,0));
  // v3 = (0,2,1), half hip (0,2,1), half knee (-1,1,1): (-0.5,1.5,1).
  Pose p = pose_at(rig, &bend, 1);
  const Positions3 at1 = {{0, 0, 0}, {1, 0, 0}, {-1, 3, 0}, {-0.5, 1.5, 1}};
  EXPECT_LT(worst(p.positions, at1), 1e-12);
  // v2's normal: (0,0,1) + (1,0,0) renormalised, then turned: (0,1,1)/sqrt 2.
  EXPECT_LT((p.normals[2] - unit(0, 1, 1)).norm(), 1e-12);
  EXPECT_LT((p.normals[3] - Vec3(0, 0, 1)).norm(), 1e-12);
  // t = 0.25: weight still 0 (STEP to 0.5), knee at 22.5 degrees: the bind, skinned.
  p = pose_at(rig, &bend, 0.25);
  const double c = std::cos(M_PI / 8), s = std::sin(M_PI / 8);
  const Positions3 at025 = {{0, 0, 0}, {1, 0, 0}, {c - s, s + c + 1, 0}, {-s / 2, (3 + c) / 2, 0}};
  EXPECT_LT(worst(p.positions, at025), 1e-6);  // the 90-degree key is stored as float32
  // The mesh node has no transform: frames are the world pose.
  EXPECT_LT(worst(node_space_pose_at(rig, &bend, 1).positions, at1), 1e-12);
}

TEST(GltfMorph, StaticCopiesDropTheMorphsAndValidate) {
  const fs::path dir = temp_dir();
  std::vector<std::string> written;
  for (const char* name : {"morph_quads.gltf", "skinned_morph.gltf"}) {
    SCOPED_TRACE(name);
    const MeshFile character = read_gltf_file(morph_file(name), {});
    RigOptions o;
    o.animation = "0";
    const RigClip rc = rig_clip(character, o);
    for (size_t k = 0; k < rc.times.size(); ++k) {
      const MeshFile frame = rig_frame(character, rc, k);
      const Pose expected =
          node_space_pose_at(rc.rig, &rc.rig.animations[rc.animation], rc.times[k]);
      EXPECT_EQ(frame.gltf->raw_positions, expected.positions);
      for (const char* ext : {".glb", ".gltf"}) {
        const std::string out = (dir / (rc.names[k] + ext)).string();
        write_gltf_file(frame, SlidVertices{}, out);
        written.push_back(out);
        const MeshFile back = read_gltf_file(out, {});
        EXPECT_LT(worst(back.gltf->raw_positions, expected.positions), 1e-6);
        const tinygltf::Model& m = back.gltf->model;
        for (const auto& prim : m.meshes[0].primitives) EXPECT_TRUE(prim.targets.empty());
        EXPECT_TRUE(m.meshes[0].weights.empty());
        for (const auto& node : m.nodes) {
          EXPECT_TRUE(node.weights.empty());
          EXPECT_EQ(node.skin, -1);
        }
        for (const auto& a : m.animations)
          for (const auto& c : a.channels) EXPECT_NE(c.target_path, "weights");
      }
    }
  }
  // morph_quads: "step" animated weights only and is gone; "cubic" keeps the root's translation
  // (its sampler renumbered 2 -> 0); "move" stays.
  const MeshFile back = read_gltf_file(written.front(), {});
  const auto& anims = back.gltf->model.animations;
  ASSERT_EQ(anims.size(), 2u);
  EXPECT_EQ(anims[0].name, "cubic");
  ASSERT_EQ(anims[0].channels.size(), 1u);
  ASSERT_EQ(anims[0].samplers.size(), 1u);
  EXPECT_EQ(anims[0].channels[0].sampler, 0);
  EXPECT_EQ(anims[0].samplers[0].interpolation, "STEP");
  EXPECT_EQ(anims[1].name, "move");
  written.push_back(morph_file("morph_quads.gltf"));
  written.push_back(morph_file("skinned_morph.gltf"));
  written.push_back(morph_file("static_triangle.gltf"));
  SKINSLIDE_EXPECT_VALID_GLTF(written);
}

// gltf_rig on an edited copy of a file's document; the Input error's message.
std::string rig_error(const std::string& name, void (*edit)(tinygltf::Model&)) {
  const MeshFile f = read_gltf_file(morph_file(name), {});
  GltfDocument doc = *f.gltf;
  edit(doc.model);
  try {
    gltf_rig(doc, name);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    return e.what();
  }
  return "no error";
}

bool has(const std::string& s, const std::string& part) {
  const bool found = s.find(part) != std::string::npos;
  if (!found) std::printf("message: %s\n", s.c_str());
  return found;
}

TEST(GltfMorph, WhatPosesAMeshAndWhatIsRefused) {
  // Neither skinned nor morphed, and the only animation moves another node: refused.
  const std::string still = rig_error("static_triangle.gltf", [](tinygltf::Model&) {});
  EXPECT_TRUE(has(still, "static_triangle.gltf: mesh 0: is not skinned"));
  EXPECT_TRUE(has(still, "nothing poses it"));
  // The same animation on the mesh node's parent: accepted, the frames move with it.
  const MeshFile f = read_gltf_file(morph_file("static_triangle.gltf"), {});
  GltfDocument doc = *f.gltf;
  doc.model.animations[0].channels[0].target_node = 0;
  const Rig rig = gltf_rig(doc, f.path);
  const Pose p = node_space_pose_at(rig, &rig.animations[0], 0.5);
  EXPECT_EQ(p.positions, (Positions3{{0.5, 0, 0}, {1.5, 0, 0}, {0.5, 1, 0}}));
  EXPECT_TRUE(p.normals.empty());

  EXPECT_TRUE(
      has(rig_error("morph_quads.gltf",
                    [](tinygltf::Model& m) { m.meshes[0].primitives[1].targets.pop_back(); }),
          "primitive 1: has 1 morph targets, primitive 0 has 2"));
  EXPECT_TRUE(has(
      rig_error("morph_quads.gltf", [](tinygltf::Model& m) { m.meshes[0].weights.push_back(1); }),
      "mesh 0: has 3 weights for 2 morph targets"));
  EXPECT_TRUE(
      has(rig_error("morph_quads.gltf", [](tinygltf::Model& m) { m.nodes[1].weights = {1}; }),
          "node 1: has 1 weights for the 2 morph targets of its mesh"));
  EXPECT_TRUE(has(rig_error("morph_quads.gltf",
                            [](tinygltf::Model& m) {
                              // 3 numbers where 3 keys x 2 targets are needed
                              m.animations[0].samplers[0].output =
                                  m.animations[0].samplers[0].input;
                            }),
                  "weights of 2 morph targets with 3 keys needs 6"));
  EXPECT_TRUE(has(rig_error("morph_quads.gltf",
                            [](tinygltf::Model& m) {
                              m.meshes[0].primitives[0].targets[1]["POSITION"] =
                                  m.meshes[0].primitives[1].attributes["POSITION"];
                            }),
                  "primitive 0: morph target 1 POSITION accessor"));
  EXPECT_TRUE(has(rig_error("morph_quads.gltf",
                            [](tinygltf::Model& m) {
                              m.nodes[1].mesh = -1;
                              m.nodes[1].weights.clear();
                              m.nodes[2].mesh = -1;
                            }),
                  "has morph targets but no node instantiates it"));
  // A blendshape-only character is a frame source: one frame per key time of the clip.
  const MeshFile quads = read_gltf_file(morph_file("morph_quads.gltf"), {});
  RigOptions o;
  o.animation = "step";
  EXPECT_EQ(rig_clip(quads, o).times, (std::vector<double>{0, 1, 2}));
}

}  // namespace
}  // namespace skinslide
