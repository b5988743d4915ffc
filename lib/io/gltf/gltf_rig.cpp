#include "io/gltf/gltf_rig.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "io/gltf/gltf_accessor.h"
#include "io/gltf/gltf_document.h"

namespace skinslide {
namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw Error(ErrorKind::Input, where + ": " + what);
}

NodeTransform rest_transform(const tinygltf::Node& node, const std::string& where) {
  NodeTransform x;
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) fail(where, "matrix does not have 16 numbers");
    x.has_matrix = true;
    x.matrix = Eigen::Map<const Eigen::Matrix4d>(node.matrix.data());  // column-major, as glTF
    return x;
  }
  if (!node.translation.empty()) {
    if (node.translation.size() != 3) fail(where, "translation does not have 3 numbers");
    x.translation = Vec3(node.translation[0], node.translation[1], node.translation[2]);
  }
  if (!node.rotation.empty()) {
    if (node.rotation.size() != 4) fail(where, "rotation does not have 4 numbers");
    x.rotation = Quat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
  }
  if (!node.scale.empty()) {
    if (node.scale.size() != 3) fail(where, "scale does not have 3 numbers");
    x.scale = Vec3(node.scale[0], node.scale[1], node.scale[2]);
  }
  return x;
}

Interpolation interpolation(const std::string& s, const std::string& where) {
  if (s == "LINEAR" || s.empty()) return Interpolation::Linear;
  if (s == "STEP") return Interpolation::Step;
  if (s == "CUBICSPLINE") return Interpolation::CubicSpline;
  fail(where, "unknown interpolation \"" + s + "\"");
}

std::string seconds(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f s", t);
  return buf;
}

// Nodes and their parents, checked: every child exists, has one parent, and no node is its own
// ancestor.
std::vector<RigNode> rig_nodes(const tinygltf::Model& model, const std::string& path) {
  std::vector<RigNode> nodes(model.nodes.size());
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    const std::string where = path + ": node " + std::to_string(i);
    nodes[i].name = model.nodes[i].name;
    nodes[i].rest = rest_transform(model.nodes[i], where);
  }
  for (std::size_t i = 0; i < model.nodes.size(); ++i)
    for (int c : model.nodes[i].children) {
      const std::string where = path + ": node " + std::to_string(i);
      if (c < 0 || c >= static_cast<int>(model.nodes.size()))
        fail(where, "child " + std::to_string(c) + " does not exist");
      if (nodes[c].parent >= 0)
        fail(where, "node " + std::to_string(c) + " has two parents (" +
                        std::to_string(nodes[c].parent) + " and " + std::to_string(i) + ")");
      nodes[c].parent = static_cast<Index>(i);
    }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    std::size_t steps = 0;
    for (Index j = nodes[i].parent; j >= 0; j = nodes[j].parent)
      if (++steps > nodes.size()) fail(path + ": node " + std::to_string(i), "is its own ancestor");
  }
  return nodes;
}

// The mesh node: the first node giving the mesh a skin, else the first instantiating it (-1:
// none). Returns that node's skin (-1: none).
int find_mesh_node(const tinygltf::Model& model, int mesh, Index& mesh_node) {
  for (std::size_t i = 0; i < model.nodes.size(); ++i)
    if (model.nodes[i].mesh == mesh && model.nodes[i].skin >= 0) {
      mesh_node = static_cast<Index>(i);
      return model.nodes[i].skin;
    }
  for (std::size_t i = 0; i < model.nodes.size(); ++i)
    if (model.nodes[i].mesh == mesh) {
      mesh_node = static_cast<Index>(i);
      break;
    }
  return -1;
}

// Morph targets: every triangle primitive has the same number (glTF 2.0 section 3.7.2.2).
std::size_t morph_target_count(const GltfDocument& doc, const std::string& mesh_where) {
  const tinygltf::Mesh& mesh = doc.model.meshes[doc.mesh];
  std::size_t target_count = 0;
  for (std::size_t k = 0; k < doc.primitives.size(); ++k) {
    const std::size_t n = mesh.primitives[doc.primitives[k].primitive].targets.size();
    if (k == 0) target_count = n;
    if (n != target_count)
      fail(mesh_where + " primitive " + std::to_string(doc.primitives[k].primitive),
           "has " + std::to_string(n) + " morph targets, primitive " +
               std::to_string(doc.primitives[0].primitive) + " has " +
               std::to_string(target_count) + " (glTF requires the same number)");
  }
  return target_count;
}

// Something must pose the mesh: a skin, morph targets, or an animation of its node (or of a
// node above it), which then moves it rigidly (or scales it).
void require_posable(const tinygltf::Model& model, const Rig& rig, int skin_index,
                     std::size_t target_count, const std::string& mesh_where) {
  if (skin_index < 0 && target_count == 0) {
    bool moved = false;
    for (const tinygltf::Animation& a : model.animations)
      for (const tinygltf::AnimationChannel& ch : a.channels) {
        if (ch.target_path == "weights" || ch.target_node < 0 ||
            ch.target_node >= static_cast<int>(model.nodes.size()))
          continue;
        for (Index j = rig.mesh_node; j >= 0; j = rig.nodes[j].parent) moved |= j == ch.target_node;
      }
    if (!moved)
      fail(mesh_where,
           "is not skinned: no node gives it a skin; it has no morph targets, and no "
           "animation moves its node: nothing poses it");
  }
  if (skin_index < 0 && rig.mesh_node < 0)
    fail(mesh_where, "has morph targets but no node instantiates it: nothing animates them");
}

// The skin `skin_index` (>= 0): its joints and inverse bind matrices.
Skin rig_skin(const tinygltf::Model& model, int skin_index, const std::string& path) {
  Skin out;
  const tinygltf::Skin& skin = model.skins[skin_index];
  const std::string skin_where = path + ": skin " + std::to_string(skin_index);
  if (skin.joints.empty()) fail(skin_where, "has no joints");
  for (int j : skin.joints) {
    if (j < 0 || j >= static_cast<int>(model.nodes.size()))
      fail(skin_where, "joint node " + std::to_string(j) + " does not exist");
    out.joints.push_back(j);
  }
  const std::size_t joint_count = out.joints.size();
  out.inverse_bind.assign(joint_count, Mat4::Identity());
  if (skin.inverseBindMatrices >= 0) {
    const std::string w =
        skin_where + ": inverseBindMatrices accessor " + std::to_string(skin.inverseBindMatrices);
    const std::vector<double> m = gltf_accessor_values(model, skin.inverseBindMatrices, w);
    if (model.accessors[skin.inverseBindMatrices].type != TINYGLTF_TYPE_MAT4 ||
        m.size() < 16 * joint_count)
      fail(w, "must hold a MAT4 for each of the " + std::to_string(joint_count) + " joints");
    for (std::size_t j = 0; j < joint_count; ++j)
      out.inverse_bind[j] = Eigen::Map<const Eigen::Matrix4d>(m.data() + 16 * j);
  }
  return out;
}

// The primitive's morph target deltas (those not zero), appended to `targets`.
void add_primitive_targets(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                           const GltfPrimitive& gp, const std::string& where,
                           std::vector<MorphTarget>& targets) {
  for (std::size_t t = 0; t < targets.size(); ++t)
    for (const char* attribute : {"POSITION", "NORMAL"}) {
      const auto it = prim.targets[t].find(attribute);
      if (it == prim.targets[t].end()) continue;  // a target may omit either
      const std::string tw = where + ": morph target " + std::to_string(t) + " " + attribute +
                             " accessor " + std::to_string(it->second);
      const std::vector<double> d = gltf_accessor_values(model, it->second, tw);
      if (model.accessors[it->second].type != TINYGLTF_TYPE_VEC3 ||
          d.size() != 3 * static_cast<std::size_t>(gp.raw_count))
        fail(tw, "must be VEC3 with one element per vertex (" + std::to_string(gp.raw_count) + ")");
      const bool position = attribute[0] == 'P';
      MorphTarget& m = targets[t];
      for (Index v = 0; v < gp.raw_count; ++v) {
        const Vec3 delta(d[3 * v], d[3 * v + 1], d[3 * v + 2]);
        if (!delta.allFinite()) fail(tw, "element " + std::to_string(v) + " is not finite");
        if (delta == Vec3::Zero()) continue;
        (position ? m.position_vertex : m.normal_vertex).push_back(gp.raw_offset + v);
        (position ? m.position_delta : m.normal_delta).push_back(delta);
      }
    }
}

// The primitive's skin influences (JOINTS_n/WEIGHTS_n sets), appended to `influences`.
void add_primitive_influences(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                              const GltfPrimitive& gp, const std::string& where,
                              std::size_t joint_count, Influences& influences) {
  std::vector<std::vector<double>> joints, weights;
  for (int set = 0;; ++set) {
    const auto j = prim.attributes.find("JOINTS_" + std::to_string(set));
    const auto w = prim.attributes.find("WEIGHTS_" + std::to_string(set));
    if (j == prim.attributes.end() && w == prim.attributes.end()) break;
    if (j == prim.attributes.end() || w == prim.attributes.end())
      fail(where,
           "has only one of JOINTS_" + std::to_string(set) + " and WEIGHTS_" + std::to_string(set));
    const std::string jw =
        where + ": JOINTS_" + std::to_string(set) + " accessor " + std::to_string(j->second);
    const std::string ww =
        where + ": WEIGHTS_" + std::to_string(set) + " accessor " + std::to_string(w->second);
    joints.push_back(gltf_accessor_values(model, j->second, jw));
    weights.push_back(gltf_accessor_values(model, w->second, ww));
    if (model.accessors[j->second].type != TINYGLTF_TYPE_VEC4 ||
        joints.back().size() != 4 * static_cast<std::size_t>(gp.raw_count))
      fail(jw, "must be VEC4 with one element per vertex");
    if (model.accessors[w->second].type != TINYGLTF_TYPE_VEC4 ||
        weights.back().size() != 4 * static_cast<std::size_t>(gp.raw_count))
      fail(ww, "must be VEC4 with one element per vertex");
  }
  if (joints.empty()) fail(where, "has no JOINTS_0/WEIGHTS_0: it cannot be skinned");
  for (Index v = 0; v < gp.raw_count; ++v) {
    double total = 0;
    for (std::size_t s = 0; s < joints.size(); ++s)
      for (int k = 0; k < 4; ++k) {
        const double w = weights[s][4 * v + k];
        if (!(w > 0)) continue;  // zero (or malformed negative/NaN) weights carry nothing
        const double jd = joints[s][4 * v + k];
        if (jd >= static_cast<double>(joint_count))
          fail(where, "vertex " + std::to_string(v) + ": joint " +
                          std::to_string(static_cast<long long>(jd)) + " is past the skin's " +
                          std::to_string(joint_count) + " joints");
        influences.joint.push_back(static_cast<Index>(jd));
        influences.weight.push_back(w);
        total += w;
      }
    if (!(total > 0)) fail(where, "vertex " + std::to_string(v) + " has no positive skin weight");
    influences.start.push_back(static_cast<Index>(influences.joint.size()));
  }
}

// Influences (when skinned), bind positions and normals of every raw vertex, morph targets.
void add_vertices(const GltfDocument& doc, bool skinned, std::size_t target_count,
                  const std::string& mesh_where, Rig& rig) {
  const tinygltf::Model& model = doc.model;
  const tinygltf::Mesh& mesh = model.meshes[doc.mesh];
  bool all_normals = true;
  for (const GltfPrimitive& gp : doc.primitives) all_normals &= gp.normal_accessor >= 0;
  rig.bind_positions = doc.raw_positions;
  rig.targets.resize(target_count);
  for (const GltfPrimitive& gp : doc.primitives) {
    const tinygltf::Primitive& prim = mesh.primitives[gp.primitive];
    const std::string where = mesh_where + " primitive " + std::to_string(gp.primitive);
    if (all_normals) {
      const std::vector<double> normals =
          gltf_accessor_values(model, gp.normal_accessor,
                               where + ": NORMAL accessor " + std::to_string(gp.normal_accessor));
      for (Index v = 0; v < gp.raw_count; ++v)
        rig.bind_normals.emplace_back(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
    }
    add_primitive_targets(model, prim, gp, where, rig.targets);
    // JOINTS_n/WEIGHTS_n without a skin mean nothing.
    if (skinned)
      add_primitive_influences(model, prim, gp, where, rig.skin.joints.size(), rig.influences);
  }
}

// Default morph weights: the mesh node's, else the mesh's, else zeros.
std::vector<double> default_morph_weights(const GltfDocument& doc, Index mesh_node,
                                          std::size_t target_count, const std::string& path,
                                          const std::string& mesh_where) {
  std::vector<double> weights(target_count, 0.0);
  if (target_count == 0) return weights;
  const tinygltf::Mesh& mesh = doc.model.meshes[doc.mesh];
  if (!mesh.weights.empty()) {
    if (mesh.weights.size() != target_count)
      fail(mesh_where, "has " + std::to_string(mesh.weights.size()) + " weights for " +
                           std::to_string(target_count) + " morph targets");
    weights = mesh.weights;
  }
  const tinygltf::Node& node = doc.model.nodes[mesh_node];
  if (!node.weights.empty()) {
    if (node.weights.size() != target_count)
      fail(path + ": node " + std::to_string(mesh_node),
           "has " + std::to_string(node.weights.size()) + " weights for the " +
               std::to_string(target_count) + " morph targets of its mesh");
    weights = node.weights;
  }
  for (std::size_t t = 0; t < target_count; ++t)
    if (!std::isfinite(weights[t]))
      fail(mesh_where, "morph weight " + std::to_string(t) + " is not finite");
  return weights;
}

// The sampler of a channel, read and checked against the channel's path.
AnimationSampler channel_sampler(const tinygltf::Model& model, const tinygltf::Animation& src,
                                 const tinygltf::AnimationChannel& ch, ChannelPath path,
                                 std::size_t target_count, const std::string& where) {
  const tinygltf::AnimationSampler& s = src.samplers[ch.sampler];
  const std::string sw = where + " sampler " + std::to_string(ch.sampler);
  AnimationSampler out;
  out.interpolation = interpolation(s.interpolation, sw);
  out.width = path == ChannelPath::Rotation  ? 4
              : path == ChannelPath::Weights ? static_cast<int>(target_count)
                                             : 3;
  out.times =
      gltf_accessor_values(model, s.input, sw + ": input accessor " + std::to_string(s.input));
  out.values =
      gltf_accessor_values(model, s.output, sw + ": output accessor " + std::to_string(s.output));
  const std::size_t keys = out.times.size();
  const std::size_t per_key = out.width * (out.interpolation == Interpolation::CubicSpline ? 3 : 1);
  if (keys == 0) fail(sw, "has no keys");
  if (model.accessors[s.input].type != TINYGLTF_TYPE_SCALAR) fail(sw, "input must be SCALAR");
  // Weights are SCALAR, one element per target per key (x3 for CUBICSPLINE).
  const int output_width = path == ChannelPath::Weights ? 1 : out.width;
  if (gltf_component_count(model.accessors[s.output].type) != output_width ||
      out.values.size() != keys * per_key)
    fail(sw, "output has " + std::to_string(out.values.size()) + " numbers; " + ch.target_path +
                 (path == ChannelPath::Weights
                      ? " of " + std::to_string(target_count) + " morph targets"
                      : std::string()) +
                 " with " + std::to_string(keys) + " keys needs " + std::to_string(keys * per_key));
  for (std::size_t k = 1; k < keys; ++k)
    if (!(out.times[k] > out.times[k - 1]))
      fail(sw, "key times are not strictly increasing at key " + std::to_string(k));
  return out;
}

ChannelPath channel_path(const std::string& target_path, const std::string& where) {
  if (target_path == "translation") return ChannelPath::Translation;
  if (target_path == "rotation") return ChannelPath::Rotation;
  if (target_path == "scale") return ChannelPath::Scale;
  if (target_path == "weights") return ChannelPath::Weights;
  fail(where, "unknown target path \"" + target_path + "\"");
}

// Animation `a`: TRS channels of every node; the weights channel of the mesh node (other nodes'
// weights do not move this mesh).
Animation rig_animation(const tinygltf::Model& model, std::size_t a, const Rig& rig,
                        std::size_t target_count, const std::string& path) {
  const tinygltf::Animation& src = model.animations[a];
  const std::string where = path + ": animation " + std::to_string(a);
  Animation anim;
  anim.name = src.name;
  bool first = true;
  for (std::size_t c = 0; c < src.channels.size(); ++c) {
    const tinygltf::AnimationChannel& ch = src.channels[c];
    const std::string cw = where + " channel " + std::to_string(c);
    if (ch.target_node < 0) continue;
    AnimationChannel out;
    out.path = channel_path(ch.target_path, cw);
    if (ch.target_node >= static_cast<int>(model.nodes.size()))
      fail(cw, "target node " + std::to_string(ch.target_node) + " does not exist");
    if (out.path == ChannelPath::Weights) {
      if (ch.target_node != rig.mesh_node || target_count == 0) continue;
    } else if (rig.nodes[ch.target_node].rest.has_matrix) {
      fail(cw, "animates node " + std::to_string(ch.target_node) +
                   ", which has a matrix (glTF allows only TRS there)");
    }
    out.node = ch.target_node;
    if (ch.sampler < 0 || ch.sampler >= static_cast<int>(src.samplers.size()))
      fail(cw, "sampler " + std::to_string(ch.sampler) + " does not exist");
    out.sampler = channel_sampler(model, src, ch, out.path, target_count, where);
    anim.start =
        first ? out.sampler.times.front() : std::min(anim.start, out.sampler.times.front());
    anim.end = first ? out.sampler.times.back() : std::max(anim.end, out.sampler.times.back());
    first = false;
    anim.channels.push_back(std::move(out));
  }
  return anim;
}

}  // namespace

Rig gltf_rig(const GltfDocument& doc, const std::string& path) {
  const tinygltf::Model& model = doc.model;
  Rig rig;
  rig.nodes = rig_nodes(model, path);
  const int skin_index = find_mesh_node(model, doc.mesh, rig.mesh_node);
  const std::string mesh_where = path + ": mesh " + std::to_string(doc.mesh);
  const std::size_t target_count = morph_target_count(doc, mesh_where);
  require_posable(model, rig, skin_index, target_count, mesh_where);
  if (skin_index >= static_cast<int>(model.skins.size()))
    fail(mesh_where, "skin " + std::to_string(skin_index) + " does not exist");
  if (skin_index >= 0) rig.skin = rig_skin(model, skin_index, path);
  add_vertices(doc, skin_index >= 0, target_count, mesh_where, rig);
  rig.weights = default_morph_weights(doc, rig.mesh_node, target_count, path, mesh_where);
  for (std::size_t a = 0; a < model.animations.size(); ++a)
    rig.animations.push_back(rig_animation(model, a, rig, target_count, path));
  return rig;
}

Index find_animation(const Rig& rig, const std::string& want, const std::string& path) {
  std::string list;
  for (std::size_t a = 0; a < rig.animations.size(); ++a)
    list += "\n  " + std::to_string(a) + " \"" + rig.animations[a].name +
            "\": " + seconds(rig.animations[a].start) + " to " + seconds(rig.animations[a].end);
  if (rig.animations.empty()) throw Error(ErrorKind::Usage, path + ": the file has no animation");
  if (want.empty()) {
    if (rig.animations.size() == 1) return 0;
    throw Error(ErrorKind::Usage,
                path + ": " + std::to_string(rig.animations.size()) +
                    " animations; choose one with --animation NAME|INDEX:" + list);
  }
  for (std::size_t a = 0; a < rig.animations.size(); ++a)
    if (rig.animations[a].name == want) return static_cast<Index>(a);
  if (std::all_of(want.begin(), want.end(), [](unsigned char c) { return std::isdigit(c); }) &&
      want.size() < 9 && std::stoul(want) < rig.animations.size())
    return static_cast<Index>(std::stoul(want));
  throw Error(ErrorKind::Usage,
              path + ": no animation \"" + want + "\"; the animations are:" + list);
}

}  // namespace skinslide
