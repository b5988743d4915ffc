#include "io/gltf/gltf_write.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include <Eigen/Geometry>

#include "core/check.h"
#include "core/error.h"
#include "io/atomic_write.h"
#include "io/gltf/gltf_accessor.h"
#include "io/gltf/gltf_document.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

std::string base64(const unsigned char* data, std::size_t n) {
  static const char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((n + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < n; i += 3) {
    const unsigned v = (data[i] << 16) | (data[i + 1] << 8) | data[i + 2];
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += kDigits[(v >> 6) & 63];
    out += kDigits[v & 63];
  }
  if (i + 1 == n) {
    const unsigned v = data[i] << 16;
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == n) {
    const unsigned v = (data[i] << 16) | (data[i + 1] << 8);
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += kDigits[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

bool is_data_uri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

// Where the writer finds what it needs to write images back unchanged.
struct ImageWriteContext {
  fs::path source_dir;  // folder of the file read
  fs::path target_dir;  // folder of the file written
};

// External image URIs are relative to the file; a copy written elsewhere gets a URI that still
// reaches the same image. Data-URI images are re-embedded from their original bytes.
bool write_image_unchanged(const std::string*, const std::string*, const tinygltf::Image* image,
                           bool, std::string* out_uri, void* user) {
  const auto* ctx = static_cast<const ImageWriteContext*>(user);
  if (image->as_is) {
    *out_uri =
        "data:" + image->mimeType + ";base64," + base64(image->image.data(), image->image.size());
    return true;
  }
  if (image->uri.empty() || is_data_uri(image->uri)) return false;
  const fs::path uri(image->uri);
  if (uri.is_absolute() || image->uri.find("://") != std::string::npos) return false;
  std::error_code ec;
  const fs::path from = fs::weakly_canonical(ctx->target_dir, ec);
  const fs::path to = fs::weakly_canonical(ctx->source_dir / uri, ec);
  const fs::path rel = ec ? fs::path() : to.lexically_relative(from);
  *out_uri = rel.empty() ? image->uri : rel.generic_string();
  return true;
}

// Per accessor to edit: its values (as read), and the components written.
struct AccessorEdit {
  int components = 0;
  std::vector<double> values;  // #count x components
  bool changed = false;
};

bool plain_float(const tinygltf::Model& model, int accessor) {
  const tinygltf::Accessor& acc = model.accessors[accessor];
  return acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT && !acc.sparse.isSparse &&
         acc.bufferView >= 0;
}

// Writes `edit` into `model`. A plain float accessor is edited in place (only the bytes of the
// moved vertices change). A sparse, quantized or normalized one cannot hold an arbitrary float,
// so it is replaced by a new float accessor over a new buffer view at the end of buffer 0; the
// chosen mesh's primitives are re-pointed to it. Returns the accessor now holding the data.
int store_accessor(tinygltf::Model& model, int accessor, const AccessorEdit& edit,
                   const std::vector<char>& element_changed) {
  const int nc = edit.components;
  if (plain_float(model, accessor)) {
    tinygltf::Accessor& acc = model.accessors[accessor];
    std::vector<unsigned char>& data = model.buffers[model.bufferViews[acc.bufferView].buffer].data;
    for (std::size_t i = 0; i < acc.count; ++i) {
      if (!element_changed[i]) continue;
      unsigned char* p = data.data() + gltf_element_offset(model, accessor, i);
      for (int c = 0; c < nc; ++c) {
        const float f = static_cast<float>(edit.values[i * nc + c]);
        std::memcpy(p + 4 * c, &f, 4);
      }
    }
    return accessor;
  }
  if (model.buffers.empty()) model.buffers.emplace_back();
  std::vector<unsigned char>& data = model.buffers[0].data;
  while (data.size() % 4 != 0) data.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = edit.values.size() * 4;
  view.target = TINYGLTF_TARGET_ARRAY_BUFFER;
  for (double v : edit.values) {
    const float f = static_cast<float>(v);
    unsigned char b[4];
    std::memcpy(b, &f, 4);
    data.insert(data.end(), b, b + 4);
  }
  model.bufferViews.push_back(view);
  tinygltf::Accessor acc = model.accessors[accessor];
  acc.bufferView = static_cast<int>(model.bufferViews.size()) - 1;
  acc.byteOffset = 0;
  acc.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  acc.normalized = false;
  acc.sparse.isSparse = false;
  acc.sparse.count = 0;
  model.accessors.push_back(acc);
  return static_cast<int>(model.accessors.size()) - 1;
}

void update_min_max(tinygltf::Model& model, int accessor, bool required) {
  tinygltf::Accessor& acc = model.accessors[accessor];
  if (!required && acc.minValues.empty() && acc.maxValues.empty()) return;
  const int nc = gltf_component_count(acc.type);
  // Bounds of the values as stored (float), so that they hold exactly.
  const std::vector<double> v = gltf_accessor_values(model, accessor, "accessor");
  std::vector<double> lo(nc, 0.0), hi(nc, 0.0);
  for (std::size_t i = 0; i < acc.count; ++i)
    for (int c = 0; c < nc; ++c) {
      const double x = v[i * nc + c];
      if (i == 0 || x < lo[c]) lo[c] = x;
      if (i == 0 || x > hi[c]) hi[c] = x;
    }
  acc.minValues = lo;
  acc.maxValues = hi;
}

Vec3 normalized_or(const Vec3& v, const Vec3& fallback) {
  const double n = v.norm();
  return n > 0 && std::isfinite(n) ? Vec3(v / n) : fallback;
}

// Stores every changed accessor (store_accessor), updates its min/max, and re-points the chosen
// mesh's primitives to any replacement. Returns old -> new accessor for the replaced ones.
std::map<int, int> store_edits(tinygltf::Model& model, const GltfDocument& doc,
                               const std::map<int, AccessorEdit>& edits,
                               const std::map<int, std::vector<char>>& changed) {
  std::map<int, int> moved;
  tinygltf::Mesh& mesh = model.meshes[doc.mesh];
  for (const auto& [accessor, c] : changed) {
    // A named copy: clang 14 cannot capture a structured binding in a lambda.
    const int edited = accessor;
    const bool is_position =
        std::any_of(doc.primitives.begin(), doc.primitives.end(),
                    [&](const GltfPrimitive& p) { return p.position_accessor == edited; });
    const int stored = store_accessor(model, accessor, edits.at(accessor), c);
    update_min_max(model, stored, is_position);
    if (stored == accessor) continue;
    moved[accessor] = stored;
    for (const GltfPrimitive& gp : doc.primitives)
      for (auto& [name, a] : mesh.primitives[gp.primitive].attributes)
        if (a == accessor) a = stored;
  }
  return moved;
}

// Serialises `model` to memory and writes it atomically: never a partial file
// (io/atomic_write.h). `.glb` gives a GLB; anything else a .gltf with one .bin per buffer beside
// it.
void write_model(tinygltf::Model model, const std::string& source_path,
                 const std::string& out_path) {
  const bool binary = has_glb_extension(out_path);
  ImageWriteContext ctx{fs::path(source_path).parent_path(), fs::path(out_path).parent_path()};
  if (ctx.source_dir.empty()) ctx.source_dir = ".";
  if (ctx.target_dir.empty()) ctx.target_dir = ".";
  tinygltf::TinyGLTF writer;
  writer.SetImageWriter(write_image_unchanged, &ctx);
  if (binary && !model.buffers.empty()) model.buffers[0].uri.clear();  // buffer 0 -> BIN chunk
  std::ostringstream out;
  if (!writer.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/!binary, binary) || !out)
    throw Error(ErrorKind::Output, out_path + ": cannot write: glTF serialisation failed");
  std::string text = std::move(out).str();
  if (binary) {
    write_file_atomic(out_path, text);
    return;
  }
  // .gltf: the serialiser embeds buffers as data URIs; each becomes a .bin beside the file,
  // named after it (several frames may share a folder, so never after the input's .bin).
  const fs::path target(out_path);
  const std::string stem = target.stem().string();
  std::size_t cursor = 0;
  std::vector<std::pair<std::string, const std::vector<unsigned char>*>> bins;
  for (std::size_t b = 0; b < model.buffers.size(); ++b) {
    const std::vector<unsigned char>& data = model.buffers[b].data;
    const std::string embedded =
        "\"data:application/octet-stream;base64," + base64(data.data(), data.size()) + "\"";
    const std::size_t at = text.find(embedded, cursor);
    SKINSLIDE_CHECK(at != std::string::npos, "serialised buffer not found in the glTF text");
    const std::string name = stem + (b == 0 ? std::string() : "_" + std::to_string(b)) + ".bin";
    const std::string quoted = "\"" + name + "\"";
    text.replace(at, embedded.size(), quoted);
    cursor = at + quoted.size();
    bins.emplace_back((target.parent_path() / name).string(), &data);
  }
  for (const auto& [bin_path, data] : bins)
    write_file_atomic(bin_path,
                      std::string_view(reinterpret_cast<const char*>(data->data()), data->size()));
  write_file_atomic(out_path, text);
}

// A static copy must not be morphed a second time by a viewer: the mesh loses its morph targets
// and default weights, the nodes instantiating it their weights, and the clips the weights
// channels of those nodes (a sampler left unused goes too, and a clip left without channels).
void drop_morph_targets(tinygltf::Model& model, int mesh) {
  for (tinygltf::Primitive& prim : model.meshes[mesh].primitives) prim.targets.clear();
  model.meshes[mesh].weights.clear();
  std::set<int> nodes;
  for (std::size_t i = 0; i < model.nodes.size(); ++i)
    if (model.nodes[i].mesh == mesh) {
      nodes.insert(static_cast<int>(i));
      model.nodes[i].weights.clear();
    }
  for (auto a = model.animations.begin(); a != model.animations.end();) {
    auto& channels = a->channels;
    const auto removed = std::remove_if(channels.begin(), channels.end(), [&](const auto& c) {
      return c.target_path == "weights" && nodes.count(c.target_node) > 0;
    });
    if (removed == channels.end()) {
      ++a;
      continue;
    }
    channels.erase(removed, channels.end());
    if (channels.empty()) {
      a = model.animations.erase(a);
      continue;
    }
    std::vector<int> renumbered(a->samplers.size(), -1);
    for (const auto& c : channels)
      if (c.sampler >= 0 && c.sampler < static_cast<int>(renumbered.size()))
        renumbered[c.sampler] = 0;
    std::vector<tinygltf::AnimationSampler> kept;
    for (std::size_t s = 0; s < a->samplers.size(); ++s)
      if (renumbered[s] == 0) {
        renumbered[s] = static_cast<int>(kept.size());
        kept.push_back(a->samplers[s]);
      }
    for (auto& c : channels)
      if (c.sampler >= 0 && c.sampler < static_cast<int>(renumbered.size()))
        c.sampler = renumbered[c.sampler];
    a->samplers = std::move(kept);
    ++a;
  }
}

}  // namespace

void write_gltf_file(const MeshFile& frame, const SlidVertices& slid, const std::string& out_path) {
  SKINSLIDE_CHECK(frame.gltf != nullptr, "write_gltf_file on a file that is not glTF");
  const GltfDocument& doc = *frame.gltf;
  SKINSLIDE_CHECK(
      slid.vertex.size() == slid.sample.size() && slid.vertex.size() == slid.position.size(),
      "slid vertices, samples and positions differ in count");
  tinygltf::Model model = doc.model;
  const Index raw_total = static_cast<Index>(doc.welded.size());
  const Index welded_total = frame.mesh.vertex_count();

  // Raw vertices of each welded vertex (CSR): every raw copy of a moved vertex moves with it.
  std::vector<Index> start(welded_total + 1, 0), raws(raw_total);
  for (Index r = 0; r < raw_total; ++r) ++start[doc.welded[r] + 1];
  for (Index v = 0; v < welded_total; ++v) start[v + 1] += start[v];
  {
    std::vector<Index> fill(start.begin(), start.end() - 1);
    for (Index r = 0; r < raw_total; ++r) raws[fill[doc.welded[r]]++] = r;
  }

  // Current data of every attribute accessor of the mesh, read once.
  const std::string where = frame.path + ": mesh " + std::to_string(doc.mesh);
  std::map<int, AccessorEdit> edits;
  auto edit_of = [&](int accessor, int components) -> AccessorEdit& {
    auto it = edits.find(accessor);
    if (it != edits.end()) return it->second;
    AccessorEdit& e = edits[accessor];
    e.components = components;
    e.values =
        gltf_accessor_values(model, accessor, where + ": accessor " + std::to_string(accessor));
    return e;
  };
  std::map<int, std::vector<char>> changed;
  auto mark = [&](int accessor, Index element) {
    std::vector<char>& c = changed[accessor];
    if (c.empty()) c.assign(model.accessors[accessor].count, 0);
    c[element] = 1;
  };
  auto primitive_of_raw = [&](Index r) -> const GltfPrimitive& {
    auto it = std::upper_bound(doc.primitives.begin(), doc.primitives.end(), r,
                               [](Index x, const GltfPrimitive& p) { return x < p.raw_offset; });
    return *(it - 1);
  };
  auto read3 = [&](int accessor, int components, Index element) {
    const AccessorEdit& e = edit_of(accessor, components);
    const double* p = e.values.data() + static_cast<std::size_t>(element) * components;
    return Vec3(p[0], p[1], p[2]);
  };

  // Normals are interpolated from the frame as read, before any of them is overwritten.
  struct Pending {
    Index raw;
    Vec3 position;
    bool has_normal = false, has_tangent = false;
    Vec3 normal, tangent;
  };
  std::vector<Pending> pending;
  for (std::size_t i = 0; i < slid.vertex.size(); ++i) {
    const Index v = slid.vertex[i];
    const SurfaceSample& s = slid.sample[i];
    SKINSLIDE_CHECK(v >= 0 && v < welded_total, "slid vertex out of range");
    SKINSLIDE_CHECK(s.face >= 0 && s.face < static_cast<Index>(doc.triangle_raw.size()),
                    "slid sample face out of range");
    const auto& tri = doc.triangle_raw[s.face];
    const GltfPrimitive& tp = doc.primitives[doc.triangle_primitive[s.face]];
    Vec3 n = Vec3::Zero(), t = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      SKINSLIDE_CHECK(s.corner[k] >= 0 && s.corner[k] < 3, "triangle corner slot out of range");
      const Index corner = tri[s.corner[k]] - tp.raw_offset;
      if (tp.normal_accessor >= 0) n += s.weight[k] * read3(tp.normal_accessor, 3, corner);
      if (tp.tangent_accessor >= 0) t += s.weight[k] * read3(tp.tangent_accessor, 4, corner);
    }
    for (Index j = start[v]; j < start[v + 1]; ++j) {
      Pending p;
      p.raw = raws[j];
      p.position = slid.position[i];
      const GltfPrimitive& rp = primitive_of_raw(p.raw);
      const Index e = p.raw - rp.raw_offset;
      // The landing triangle's primitive may lack NORMAL/TANGENT; then the copy keeps its own.
      if (rp.normal_accessor >= 0 && tp.normal_accessor >= 0) {
        p.has_normal = true;
        p.normal = normalized_or(n, read3(rp.normal_accessor, 3, e));
      }
      if (rp.tangent_accessor >= 0 && tp.tangent_accessor >= 0) {
        p.has_tangent = true;
        p.tangent = normalized_or(t, read3(rp.tangent_accessor, 4, e));
      }
      pending.push_back(p);
    }
  }
  for (const Pending& p : pending) {
    const GltfPrimitive& rp = primitive_of_raw(p.raw);
    const Index e = p.raw - rp.raw_offset;
    AccessorEdit& pe = edit_of(rp.position_accessor, 3);
    for (int c = 0; c < 3; ++c) pe.values[3 * e + c] = p.position[c];
    mark(rp.position_accessor, e);
    if (p.has_normal) {
      AccessorEdit& ne = edit_of(rp.normal_accessor, 3);
      for (int c = 0; c < 3; ++c) ne.values[3 * e + c] = p.normal[c];
      mark(rp.normal_accessor, e);
    }
    if (p.has_tangent) {
      AccessorEdit& te = edit_of(rp.tangent_accessor, 4);
      for (int c = 0; c < 3; ++c) te.values[4 * e + c] = p.tangent[c];  // w (handedness) kept
      mark(rp.tangent_accessor, e);
    }
  }

  store_edits(model, doc, edits, changed);
  write_model(std::move(model), frame.path, out_path);
}

MeshFile posed_gltf_file(const MeshFile& character, const Positions3& raw_positions,
                         const Positions3& raw_normals) {
  SKINSLIDE_CHECK(character.gltf != nullptr, "posed_gltf_file on a file that is not glTF");
  auto doc = std::make_shared<GltfDocument>(*character.gltf);
  SKINSLIDE_CHECK(raw_positions.size() == doc->welded.size(), "one posed position per raw vertex");
  SKINSLIDE_CHECK(raw_normals.empty() || raw_normals.size() == doc->welded.size(),
                  "one posed normal per raw vertex");
  tinygltf::Model& model = doc->model;
  std::map<int, AccessorEdit> edits;
  std::map<int, std::vector<char>> changed;
  auto set_all = [&](int accessor, int components, const GltfPrimitive& gp, const Positions3& v) {
    AccessorEdit& e = edits[accessor];
    if (e.values.empty()) {
      e.components = components;
      e.values = gltf_accessor_values(model, accessor,
                                      character.path + ": accessor " + std::to_string(accessor));
    }
    for (Index i = 0; i < gp.raw_count; ++i)
      for (int c = 0; c < 3; ++c)
        e.values[static_cast<std::size_t>(i) * components + c] = v[gp.raw_offset + i][c];
    changed[accessor].assign(model.accessors[accessor].count, 1);
  };
  for (const GltfPrimitive& gp : doc->primitives) {
    set_all(gp.position_accessor, 3, gp, raw_positions);
    if (gp.normal_accessor >= 0 && !raw_normals.empty())
      set_all(gp.normal_accessor, 3, gp, raw_normals);
  }
  const std::map<int, int> moved = store_edits(model, *doc, edits, changed);
  for (GltfPrimitive& gp : doc->primitives) {
    if (moved.count(gp.position_accessor)) gp.position_accessor = moved.at(gp.position_accessor);
    if (moved.count(gp.normal_accessor)) gp.normal_accessor = moved.at(gp.normal_accessor);
  }
  // The posed copy is static: left skinned, a viewer would deform it a second time.
  for (tinygltf::Node& node : model.nodes)
    if (node.mesh == doc->mesh) node.skin = -1;
  for (tinygltf::Primitive& prim : model.meshes[doc->mesh].primitives)
    for (auto it = prim.attributes.begin(); it != prim.attributes.end();)
      it = it->first.rfind("JOINTS_", 0) == 0 || it->first.rfind("WEIGHTS_", 0) == 0
               ? prim.attributes.erase(it)
               : std::next(it);
  drop_morph_targets(model, doc->mesh);
  doc->raw_positions = raw_positions;

  MeshFile out;
  out.path = character.path;
  out.format = character.format;
  out.mesh = character.mesh;
  std::vector<char> seen(out.mesh.vertex_count(), 0);
  for (std::size_t r = 0; r < doc->welded.size(); ++r) {
    const Index v = doc->welded[r];
    if (seen[v]) continue;  // a welded vertex takes its first raw copy's pose
    seen[v] = 1;
    out.mesh.positions[v] = raw_positions[r];
  }
  out.gltf = std::move(doc);
  return out;
}

MeshFile gltf_at_positions(const MeshFile& bind, const Positions3& positions) {
  SKINSLIDE_CHECK(bind.gltf != nullptr, "gltf_at_positions on a file that is not glTF");
  const GltfDocument& doc = *bind.gltf;
  SKINSLIDE_CHECK(positions.size() == static_cast<std::size_t>(bind.mesh.vertex_count()),
                  "one position per welded vertex");
  const std::size_t raw_total = doc.welded.size();
  Positions3 raw(raw_total), normals(raw_total, Vec3::Zero());
  for (std::size_t r = 0; r < raw_total; ++r) raw[r] = positions[doc.welded[r]];
  for (const std::array<Index, 3>& t : doc.triangle_raw) {
    const Vec3 n = (raw[t[1]] - raw[t[0]]).cross(raw[t[2]] - raw[t[0]]);
    for (Index r : t) normals[r] += n;
  }
  // A raw vertex whose triangles have no area takes its welded vertex's normal, else +z.
  Positions3 welded_normals(positions.size(), Vec3::Zero());
  for (std::size_t r = 0; r < raw_total; ++r) welded_normals[doc.welded[r]] += normals[r];
  for (std::size_t r = 0; r < raw_total; ++r) {
    Vec3 n = normals[r].norm() > 0 ? normals[r] : welded_normals[doc.welded[r]];
    normals[r] = n.norm() > 0 ? Vec3(n.normalized()) : Vec3::UnitZ();
  }
  return posed_gltf_file(bind, raw, normals);
}

}  // namespace skinslide
