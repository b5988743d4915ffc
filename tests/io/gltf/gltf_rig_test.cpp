// The rig read from glTF and posed by pose/, against a second evaluation written here from the
// file alone: tinygltf's raw model, plain arrays, the spec's formulas spelled out.
#include "io/gltf/gltf_rig.h"

#include <cmath>
#include <cstring>
#include <filesystem>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "core/error.h"
#include "io/gltf/gltf.h"
#include "io/gltf/gltf_document.h"
#include "helpers/samples.h"
#include "io/gltf/gltf_test_util.h"
#include "pipeline/rig_frames.h"
#include "pose/animation.h"
#include "pose/skinning.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;
using testing::shared_gltf;
using testing::temp_dir;

// ----- The reference: column-major 4x4 arrays, m[c * 4 + r] as glTF stores them. -----------

using M4 = std::array<double, 16>;

M4 mul(const M4& a, const M4& b) {
  M4 r{};
  for (int c = 0; c < 4; ++c)
    for (int rr = 0; rr < 4; ++rr)
      for (int k = 0; k < 4; ++k) r[c * 4 + rr] += a[k * 4 + rr] * b[c * 4 + k];
  return r;
}

M4 trs(const double t[3], const double q[4], const double s[3]) {
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                          {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                          {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
  M4 m{};
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) m[c * 4 + r] = R[r][c] * s[c];
  m[12] = t[0];
  m[13] = t[1];
  m[14] = t[2];
  m[15] = 1;
  return m;
}

struct Reference {
  tinygltf::Model model;

  std::vector<float> floats(int accessor) const {
    const auto& a = model.accessors[accessor];
    const auto& v = model.bufferViews[a.bufferView];
    const int n = tinygltf::GetNumComponentsInType(a.type);
    const size_t stride = v.byteStride ? v.byteStride : 4 * n;
    const unsigned char* p = model.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset;
    std::vector<float> out(a.count * n);
    for (size_t i = 0; i < a.count; ++i) std::memcpy(&out[i * n], p + i * stride, 4 * n);
    return out;
  }
  std::vector<int> shorts(int accessor) const {  // JOINTS_0 (unsigned short in all four)
    const auto& a = model.accessors[accessor];
    const auto& v = model.bufferViews[a.bufferView];
    const size_t stride = v.byteStride ? v.byteStride : 8;
    const unsigned char* p = model.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset;
    std::vector<int> out(a.count * 4);
    for (size_t i = 0; i < a.count; ++i)
      for (int k = 0; k < 4; ++k) {
        std::uint16_t j;
        std::memcpy(&j, p + i * stride + 2 * k, 2);
        out[i * 4 + k] = j;
      }
    return out;
  }

  // LINEAR only (every sampler of the four characters): lerp, or slerp for rotations.
  std::vector<double> sampled(const tinygltf::AnimationSampler& s, int width, double t) const {
    const std::vector<float> in = floats(s.input), out = floats(s.output);
    const size_t n = in.size();
    auto key = [&](size_t k) {
      return std::vector<double>(out.begin() + k * width, out.begin() + (k + 1) * width);
    };
    if (t <= in[0]) return key(0);
    if (t >= in[n - 1]) return key(n - 1);
    size_t k = 0;
    while (!(in[k] <= t && t < in[k + 1])) ++k;
    const double u = (t - in[k]) / (in[k + 1] - in[k]);
    std::vector<double> a = key(k), b = key(k + 1), r(width);
    if (width == 3) {
      for (int c = 0; c < 3; ++c) r[c] = a[c] + u * (b[c] - a[c]);
      return r;
    }
    double d = 0;
    for (int c = 0; c < 4; ++c) d += a[c] * b[c];
    if (d < 0) {
      for (double& x : b) x = -x;
      d = -d;
    }
    double wa = 1 - u, wb = u;
    if (d < 0.9995) {
      const double th = std::acos(d);
      wa = std::sin((1 - u) * th) / std::sin(th);
      wb = std::sin(u * th) / std::sin(th);
    }
    double len = 0;
    for (int c = 0; c < 4; ++c) len += (r[c] = wa * a[c] + wb * b[c]) * r[c];
    for (double& x : r) x /= std::sqrt(len);
    return r;
  }

  M4 world(int node, const std::vector<M4>& local) const {
    for (size_t p = 0; p < model.nodes.size(); ++p)
      for (int c : model.nodes[p].children)
        if (c == node) return mul(world(static_cast<int>(p), local), local[node]);
    return local[node];
  }

  // Posed raw vertices of mesh 0 primitive 0 at time t of animation `anim`.
  std::vector<std::array<double, 3>> pose(int anim, double t) const {
    std::vector<std::array<double, 3>> T(model.nodes.size()), S(model.nodes.size());
    std::vector<std::array<double, 4>> R(model.nodes.size());
    std::vector<M4> local(model.nodes.size());
    for (size_t i = 0; i < model.nodes.size(); ++i) {
      const auto& n = model.nodes[i];
      T[i] = {0, 0, 0};
      R[i] = {0, 0, 0, 1};
      S[i] = {1, 1, 1};
      for (size_t c = 0; c < n.translation.size(); ++c) T[i][c] = n.translation[c];
      for (size_t c = 0; c < n.rotation.size(); ++c) R[i][c] = n.rotation[c];
      for (size_t c = 0; c < n.scale.size(); ++c) S[i][c] = n.scale[c];
    }
    for (const auto& ch : model.animations[anim].channels) {
      const auto& s = model.animations[anim].samplers[ch.sampler];
      const int w = ch.target_path == "rotation" ? 4 : 3;
      const std::vector<double> v = sampled(s, w, t);
      for (int c = 0; c < w; ++c) {
        if (ch.target_path == "translation") T[ch.target_node][c] = v[c];
        if (ch.target_path == "rotation") R[ch.target_node][c] = v[c];
        if (ch.target_path == "scale") S[ch.target_node][c] = v[c];
      }
    }
    for (size_t i = 0; i < model.nodes.size(); ++i) {
      if (model.nodes[i].matrix.size() == 16)
        std::copy(model.nodes[i].matrix.begin(), model.nodes[i].matrix.end(), local[i].begin());
      else
        local[i] = trs(T[i].data(), R[i].data(), S[i].data());
    }
    int mesh_node = 0;
    while (model.nodes[mesh_node].mesh != 0) ++mesh_node;
    const tinygltf::Skin& skin = model.skins[model.nodes[mesh_node].skin];
    const std::vector<float> ibm = floats(skin.inverseBindMatrices);
    std::vector<M4> joint(skin.joints.size());
    for (size_t j = 0; j < skin.joints.size(); ++j) {
      M4 inv;
      std::copy(ibm.begin() + 16 * j, ibm.begin() + 16 * (j + 1), inv.begin());
      joint[j] = mul(world(skin.joints[j], local), inv);
    }
    const auto& prim = model.meshes[0].primitives[0];
    const std::vector<float> pos = floats(prim.attributes.at("POSITION"));
    const std::vector<float> wts = floats(prim.attributes.at("WEIGHTS_0"));
    const std::vector<int> jts = shorts(prim.attributes.at("JOINTS_0"));
    std::vector<std::array<double, 3>> out(pos.size() / 3);
    for (size_t v = 0; v < out.size(); ++v) {
      double sum = 0, p[3] = {0, 0, 0};
      for (int k = 0; k < 4; ++k) {
        const double w = wts[4 * v + k];
        const M4& m = joint[jts[4 * v + k]];
        sum += w;
        for (int r = 0; r < 3; ++r)
          p[r] += w * (m[r] * pos[3 * v] + m[4 + r] * pos[3 * v + 1] + m[8 + r] * pos[3 * v + 2] +
                       m[12 + r]);
      }
      for (int r = 0; r < 3; ++r) out[v][r] = p[r] / sum;
    }
    return out;
  }
};

TEST(GltfRig, PosingAgreesWithAnIndependentEvaluationOnAllFourCharacters) {
  SKINSLIDE_REQUIRE_GLTF("CesiumMan.glb", "Fox.glb", "RiggedFigure.glb", "RiggedSimple.glb");
  for (const char* name : {"RiggedSimple.glb", "RiggedFigure.glb", "CesiumMan.glb", "Fox.glb"}) {
    SCOPED_TRACE(name);
    Reference ref;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&ref.model, &err, &warn, shared_gltf(name))) << err;
    const MeshFile f = read_gltf_file(shared_gltf(name), {});
    const Rig rig = gltf_rig(*f.gltf, f.path);
    const double diag = test::diagonal(rig.bind_positions);
    double worst = 0;
    for (size_t a = 0; a < rig.animations.size(); ++a) {
      const Animation& anim = rig.animations[a];
      std::vector<double> times = keyframe_times(anim);
      // Between keys too, and outside the clip (clamped).
      for (size_t k = 0; k + 1 < keyframe_times(anim).size(); k += 3)
        times.push_back(times[k] + (times[k + 1] - times[k]) / 3);
      times.push_back(anim.start - 1);
      times.push_back(anim.end + 1);
      for (double t : times) {
        const Pose p = pose_at(rig, &anim, t);
        const auto q = ref.pose(static_cast<int>(a), t);
        ASSERT_EQ(p.positions.size(), q.size());
        for (size_t v = 0; v < q.size(); ++v)
          worst = std::max(worst, (p.positions[v] - Vec3(q[v][0], q[v][1], q[v][2])).norm());
      }
    }
    EXPECT_LT(worst, 1e-5 * diag);
    std::printf("[ posing  ] %s: max |skinslide - reference| = %.3g = %.3g of the diagonal\n", name,
                worst, worst / diag);
  }
}

TEST(GltfRig, RestSkinningIsTheStoredMeshUnderARigidMap) {
  SKINSLIDE_REQUIRE_GLTF("CesiumMan.glb", "Fox.glb", "RiggedFigure.glb", "RiggedSimple.glb");
  // The bind is POSITION as stored. At the nodes' stored transforms skinning gives it back up to
  // a rigid change of axes (Z_UP and Armature matrices): checked through edge lengths.
  for (const char* name : {"RiggedSimple.glb", "RiggedFigure.glb", "CesiumMan.glb", "Fox.glb"}) {
    SCOPED_TRACE(name);
    const MeshFile f = read_gltf_file(shared_gltf(name), {});
    const Rig rig = gltf_rig(*f.gltf, f.path);
    const Pose rest = pose_at(rig, nullptr, 0);
    const double diag = test::diagonal(rig.bind_positions);
    double worst = 0;
    for (const auto& t : f.gltf->triangle_raw)
      for (int k = 0; k < 3; ++k) {
        const Index a = t[k], b = t[(k + 1) % 3];
        worst = std::max(worst, std::abs((rest.positions[a] - rest.positions[b]).norm() -
                                         (rig.bind_positions[a] - rig.bind_positions[b]).norm()));
      }
    EXPECT_LT(worst, 1e-6 * diag);
  }
}

TEST(GltfRig, ReadsTheDocumentedSkeletonsAndClips) {
  SKINSLIDE_REQUIRE_GLTF("Fox.glb");
  const MeshFile fox = read_gltf_file(shared_gltf("Fox.glb"), {});
  const Rig rig = gltf_rig(*fox.gltf, fox.path);
  EXPECT_EQ(rig.skin.joints.size(), 24u);
  ASSERT_EQ(rig.animations.size(), 3u);
  EXPECT_EQ(rig.animations[1].name, "Walk");
  EXPECT_EQ(rig.animations[1].channels.size(), 21u);
  EXPECT_EQ(keyframe_times(rig.animations[1]).size(), 18u);
  EXPECT_TRUE(rig.bind_normals.empty());  // Fox has no NORMAL
  EXPECT_EQ(find_animation(rig, "Run", fox.path), 2);
  EXPECT_EQ(find_animation(rig, "1", fox.path), 1);
  try {
    find_animation(rig, "", fox.path);
    FAIL() << "expected a usage error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("1 \"Walk\": 0.000 s to 0.708 s"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(find_animation(rig, "Jump", fox.path), Error);
}

TEST(RigFrames, FramesAreStaticPosedCopiesThatValidate) {
  SKINSLIDE_REQUIRE_GLTF("RiggedSimple.glb");
  const fs::path dir = temp_dir();
  const MeshFile character = read_gltf_file(shared_gltf("RiggedSimple.glb"), {});
  const RigClip clip = rig_clip(character, {});
  ASSERT_EQ(clip.times.size(), 50u);
  EXPECT_EQ(clip.names.front(), "RiggedSimple.0000");
  EXPECT_EQ(clip.names.back(), "RiggedSimple.0049");
  std::vector<std::string> written;
  const std::vector<Mat4> rest_world =
      world_matrices(clip.rig, animated_transforms(clip.rig, nullptr, 0));
  for (size_t k : {size_t{0}, size_t{25}, size_t{49}}) {
    const MeshFile frame = rig_frame(character, clip, k);
    EXPECT_TRUE(same_faces(frame.mesh, character.mesh));
    // Shown through the mesh node's transform, the frame is where the skinned character is.
    const Pose world = pose_at(clip.rig, &clip.rig.animations[0], clip.times[k]);
    const Mat4& m = rest_world[clip.rig.mesh_node];
    for (size_t r = 0; r < world.positions.size(); ++r) {
      const Vec3 shown =
          m.topLeftCorner<3, 3>() * frame.gltf->raw_positions[r] + m.topRightCorner<3, 1>();
      ASSERT_LT((shown - world.positions[r]).norm(), 1e-9);
    }
    const std::string out = (dir / (clip.names[k] + ".glb")).string();
    write_gltf_file(frame, SlidVertices{}, out);
    const MeshFile back = read_gltf_file(out, {});
    for (size_t r = 0; r < world.positions.size(); ++r)
      ASSERT_LT((back.gltf->raw_positions[r] - frame.gltf->raw_positions[r]).norm(), 1e-5);
    EXPECT_THROW(gltf_rig(*back.gltf, out), Error);  // no longer skinned
    written.push_back(out);
  }
  SKINSLIDE_EXPECT_VALID_GLTF(written);
}

TEST(RigFrames, FpsSamplingAndUnskinnedFilesAreRefusedClearly) {
  SKINSLIDE_REQUIRE_GLTF("Fox.glb");
  const MeshFile character = read_gltf_file(shared_gltf("Fox.glb"), {});
  RigOptions o;
  o.animation = "Walk";
  o.fps = 30;
  const RigClip clip = rig_clip(character, o);
  EXPECT_EQ(clip.times.size(), 22u);  // 0 .. 0.7083 s every 1/30 s
  EXPECT_EQ(clip.names[21], "Fox.0021");
  const fs::path dir = temp_dir();
  const std::string still = (dir / "still.glb").string();
  write_gltf_file(rig_frame(character, clip, 3), SlidVertices{}, still);
  try {
    rig_clip(read_gltf_file(still, {}), {});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_NE(std::string(e.what()).find("is not skinned"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace skinslide
