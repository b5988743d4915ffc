#include "io/gltf/gltf_read.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <set>

#include "core/check.h"
#include "core/error.h"
#include "io/atomic_write.h"
#include "io/gltf/gltf_accessor.h"
#include "io/gltf/gltf_buffer_uris.h"
#include "io/gltf/gltf_document.h"
#include "io/gltf/gltf_uri.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw Error(ErrorKind::Input, where + ": " + what);
}

bool has_glb_magic(const std::string& bytes) {
  return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

// Images are never decoded: skinslide writes them back as they were. The encoded bytes of a
// data-URI image are kept (as_is) because nothing else holds them; buffer-view images stay in
// their buffer, and external ones keep their URI and are never opened (io/gltf/gltf_uri.h).
bool keep_image_bytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && image->uri.empty()) {
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
  }
  return true;
}

std::string describe_meshes(const tinygltf::Model& model) {
  std::string s;
  for (std::size_t m = 0; m < model.meshes.size(); ++m) {
    std::size_t vertices = 0;
    std::set<int> counted;  // primitives may share a POSITION accessor
    for (const tinygltf::Primitive& p : model.meshes[m].primitives) {
      const auto it = p.attributes.find("POSITION");
      if (it != p.attributes.end() && it->second >= 0 &&
          it->second < static_cast<int>(model.accessors.size()) &&
          counted.insert(it->second).second)
        vertices += model.accessors[it->second].count;
    }
    s += "\n  " + std::to_string(m) + " \"" + model.meshes[m].name +
         "\": " + std::to_string(model.meshes[m].primitives.size()) + " primitive(s), " +
         std::to_string(vertices) + " vertices";
  }
  return s;
}

int choose_mesh(const tinygltf::Model& model, const std::string& path, const std::string& want) {
  if (model.meshes.empty()) fail(path, "the file has no mesh");
  if (want.empty()) {
    if (model.meshes.size() == 1) return 0;
    fail(path, std::to_string(model.meshes.size()) +
                   " meshes; choose one with --mesh NAME|INDEX:" + describe_meshes(model));
  }
  int found = -1;
  for (std::size_t m = 0; m < model.meshes.size(); ++m) {
    if (model.meshes[m].name != want) continue;
    if (found >= 0)
      fail(path, "several meshes are named \"" + want +
                     "\"; give its index with --mesh:" + describe_meshes(model));
    found = static_cast<int>(m);
  }
  if (found >= 0) return found;
  if (want.size() < 10 &&
      std::all_of(want.begin(), want.end(), [](unsigned char c) { return std::isdigit(c); })) {
    const unsigned long m = std::stoul(want);
    if (m < model.meshes.size()) return static_cast<int>(m);
  }
  fail(path,
       "no mesh \"" + want + "\" (by name or index); the meshes are:" + describe_meshes(model));
}

// The triangles of one primitive as element indices of its attributes (glTF 2.0 section 3.7.2.1:
// strips and fans are expanded to their triangles, in order).
std::vector<std::array<Index, 3>> primitive_triangles(const tinygltf::Model& model,
                                                      const tinygltf::Primitive& prim,
                                                      Index vertex_count,
                                                      const std::string& where) {
  std::vector<Index> ids;
  if (prim.indices >= 0) {
    const std::string iw = where + ": indices accessor " + std::to_string(prim.indices);
    if (prim.indices >= static_cast<int>(model.accessors.size())) fail(iw, "does not exist");
    const tinygltf::Accessor& acc = model.accessors[prim.indices];
    if (acc.type != TINYGLTF_TYPE_SCALAR ||
        (acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
         acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
         acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) ||
        acc.normalized)
      fail(iw, "must be SCALAR unsigned byte/short/int");
    const std::vector<double> v = gltf_accessor_values(model, prim.indices, iw);
    ids.resize(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (v[i] >= vertex_count)
        fail(iw, "index " + std::to_string(i) + " is " +
                     std::to_string(static_cast<long long>(v[i])) + ", past the " +
                     std::to_string(vertex_count) + " vertices");
      ids[i] = static_cast<Index>(v[i]);
    }
  } else {
    ids.resize(vertex_count);
    for (Index i = 0; i < vertex_count; ++i) ids[i] = i;
  }
  std::vector<std::array<Index, 3>> tris;
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  const std::size_t n = ids.size();
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (n % 3 != 0) fail(where, std::to_string(n) + " triangle-list indices: not a multiple of 3");
    for (std::size_t i = 0; i < n; i += 3) tris.push_back({ids[i], ids[i + 1], ids[i + 2]});
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (std::size_t i = 0; i + 2 < n; ++i)
      tris.push_back({ids[i], ids[i + 1 + i % 2], ids[i + 2 - i % 2]});
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (std::size_t i = 0; i + 2 < n; ++i) tris.push_back({ids[i + 1], ids[i + 2], ids[0]});
  }
  return tris;
}

bool is_triangle_mode(int mode) {
  return mode < 0 || mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
         mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

int attribute(const tinygltf::Primitive& prim, const char* name) {
  const auto it = prim.attributes.find(name);
  return it == prim.attributes.end() ? -1 : it->second;
}

void check_attribute(const tinygltf::Model& model, int accessor, int type, Index count,
                     const std::string& where) {
  if (accessor < 0) return;
  if (accessor >= static_cast<int>(model.accessors.size())) fail(where, "does not exist");
  const tinygltf::Accessor& acc = model.accessors[accessor];
  if (acc.type != type)
    fail(where, "is " + gltf_type_name(acc.type) + ", expected " + gltf_type_name(type));
  if (count >= 0 && static_cast<Index>(acc.count) != count)
    fail(where,
         "has " + std::to_string(acc.count) + " elements, POSITION has " + std::to_string(count));
}

// The file at `path` parsed by tinygltf. Every buffer URI is judged (io/gltf/gltf_uri.h) before
// tinygltf opens a file, and tinygltf then opens only the files so approved: no byte from outside
// the glTF's folder and the trusted trees is read, and no image at all.
std::shared_ptr<GltfDocument> load_document(const std::string& path,
                                            const MeshReadOptions& options) {
  const std::string bytes = read_file(path);
  if (const std::optional<JsonFault> fault = gltf_integer_fault(bytes))
    fail(path, fault->element + ": " + fault->what);
  auto doc = std::make_shared<GltfDocument>();
  ApprovedFiles files = approved_buffer_files(path, bytes, options.allow_uri_outside);
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(approved_files_only(files));
  loader.SetImageLoader(keep_image_bytes, nullptr);
  std::string err, warn;
  const std::string base_dir = fs::path(path).parent_path().string();
  doc->binary = has_glb_magic(bytes);
  const bool ok =
      doc->binary
          ? loader.LoadBinaryFromMemory(&doc->model, &err, &warn,
                                        reinterpret_cast<const unsigned char*>(bytes.data()),
                                        static_cast<unsigned>(bytes.size()), base_dir)
          : loader.LoadASCIIFromString(&doc->model, &err, &warn, bytes.data(),
                                       static_cast<unsigned>(bytes.size()), base_dir);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    std::replace(err.begin(), err.end(), '\n', ';');
    fail(path,
         "not a readable glTF 2.0 file: " + (err.empty() ? std::string("unknown error") : err));
  }
  doc->files_read = std::move(files.read);
  return doc;
}

}  // namespace

// An open-addressing table over the positions' bits: a std::map node per vertex had cost a cache
// miss per level of the tree (tests/bench/README.md "Reading glTF").
std::vector<Index> weld_positions(const Positions3& raw) {
  const size_t n = raw.size();
  // Adding +0 turns -0 into +0, so equal coordinates have equal bits.
  const auto bits = [](double x) {
    std::uint64_t b;
    const double y = x + 0.0;
    std::memcpy(&b, &y, sizeof b);
    return b;
  };
  size_t capacity = 16;
  while (capacity < 2 * n) capacity *= 2;
  std::vector<Index> slot(capacity, -1);  // raw id of the first copy at a position, or -1
  std::vector<Index> welded(n);
  Index count = 0;
  for (size_t r = 0; r < n; ++r) {
    const Vec3& p = raw[r];
    std::uint64_t h = bits(p[0]) * 0x9E3779B97F4A7C15ULL;
    h = (h ^ (h >> 29) ^ bits(p[1])) * 0xBF58476D1CE4E5B9ULL;
    h = (h ^ (h >> 31) ^ bits(p[2])) * 0x94D049BB133111EBULL;
    for (size_t k = (h ^ (h >> 32)) & (capacity - 1);; k = (k + 1) & (capacity - 1)) {
      if (slot[k] < 0) {
        slot[k] = static_cast<Index>(r);
        welded[r] = count++;
        break;
      }
      if (raw[slot[k]] == p) {
        welded[r] = welded[slot[k]];
        break;
      }
    }
  }
  return welded;
}

MeshFile read_gltf_file(const std::string& path, const MeshReadOptions& options) {
  const std::shared_ptr<GltfDocument> doc = load_document(path, options);
  const tinygltf::Model& model = doc->model;
  doc->mesh = choose_mesh(model, path, options.mesh);
  const tinygltf::Mesh& mesh = model.meshes[doc->mesh];
  const std::string mesh_where = path + ": mesh " + std::to_string(doc->mesh);

  MeshFile out;
  out.path = path;
  out.format = has_glb_extension(path) ? MeshFormat::Glb : MeshFormat::Gltf;
  std::vector<std::vector<std::array<Index, 3>>> primitive_tris;  // per kept primitive
  for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& prim = mesh.primitives[p];
    const std::string where = mesh_where + " primitive " + std::to_string(p);
    if (!is_triangle_mode(prim.mode)) continue;
    for (const char* ext : {"KHR_draco_mesh_compression", "EXT_meshopt_compression"})
      if (prim.extensions.count(ext))
        fail(where, std::string("is compressed with ") + ext +
                        ", which skinslide cannot decode; decompress the file first");
    GltfPrimitive gp;
    gp.primitive = static_cast<int>(p);
    gp.position_accessor = attribute(prim, "POSITION");
    if (gp.position_accessor < 0) fail(where, "has no POSITION attribute");
    const std::string pw = where + ": POSITION accessor " + std::to_string(gp.position_accessor);
    check_attribute(model, gp.position_accessor, TINYGLTF_TYPE_VEC3, -1, pw);
    // glTF 2.0 positions are floats; KHR_mesh_quantization adds (normalized or not) 8- and
    // 16-bit integers. 32-bit integers and anything else are not positions a viewer can read.
    const int position_type = model.accessors[gp.position_accessor].componentType;
    if (position_type != TINYGLTF_COMPONENT_TYPE_FLOAT &&
        position_type != TINYGLTF_COMPONENT_TYPE_BYTE &&
        position_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        position_type != TINYGLTF_COMPONENT_TYPE_SHORT &&
        position_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)
      fail(pw, "has component type " + std::to_string(position_type) +
                   "; positions are float (5126), or 8/16-bit integers with KHR_mesh_quantization");
    const std::vector<double> pos = gltf_accessor_values(model, gp.position_accessor, pw);
    gp.raw_count = static_cast<Index>(pos.size() / 3);
    gp.raw_offset = static_cast<Index>(doc->raw_positions.size());
    gp.normal_accessor = attribute(prim, "NORMAL");
    check_attribute(model, gp.normal_accessor, TINYGLTF_TYPE_VEC3, gp.raw_count,
                    where + ": NORMAL accessor " + std::to_string(gp.normal_accessor));
    gp.tangent_accessor = attribute(prim, "TANGENT");
    check_attribute(model, gp.tangent_accessor, TINYGLTF_TYPE_VEC4, gp.raw_count,
                    where + ": TANGENT accessor " + std::to_string(gp.tangent_accessor));
    for (Index i = 0; i < gp.raw_count; ++i) {
      const double x = pos[3 * i], y = pos[3 * i + 1], z = pos[3 * i + 2];
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
        fail(pw, "vertex " + std::to_string(i) + " is not finite");
      doc->raw_positions.emplace_back(x, y, z);
    }
    primitive_tris.push_back(primitive_triangles(model, prim, gp.raw_count, where));
    doc->primitives.push_back(gp);
  }
  doc->welded = weld_positions(doc->raw_positions);
  for (size_t r = 0; r < doc->welded.size(); ++r)  // a welded vertex is at its first raw copy
    if (doc->welded[r] == out.mesh.vertex_count())
      out.mesh.positions.push_back(doc->raw_positions[r]);
  for (size_t k = 0; k < doc->primitives.size(); ++k) {
    GltfPrimitive& gp = doc->primitives[k];
    gp.first_triangle = out.mesh.face_count();
    gp.triangle_count = static_cast<Index>(primitive_tris[k].size());
    for (const auto& t : primitive_tris[k]) {
      const std::array<Index, 3> raw{gp.raw_offset + t[0], gp.raw_offset + t[1],
                                     gp.raw_offset + t[2]};
      out.mesh.add_face({doc->welded[raw[0]], doc->welded[raw[1]], doc->welded[raw[2]]});
      doc->triangle_raw.push_back(raw);
      doc->triangle_primitive.push_back(static_cast<int>(k));
    }
  }
  if (out.mesh.face_count() == 0) fail(mesh_where, "has no triangles");
  out.gltf = std::move(doc);
  return out;
}

Index gltf_raw_vertex_count(const MeshFile& file) {
  SKINSLIDE_CHECK(file.gltf != nullptr, "gltf_raw_vertex_count on a file that is not glTF");
  return static_cast<Index>(file.gltf->welded.size());
}

}  // namespace skinslide
