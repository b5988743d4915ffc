#include "io/gltf/gltf.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/atomic_write.h"
#include "io/gltf/gltf_accessor.h"
#include "io/gltf/gltf_document.h"
#include "io/gltf/gltf_test_util.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;
using testing::compare_gltf;
using testing::shared_gltf;
using testing::temp_dir;

// ---------------------------------------------------------------------------------------------
// The four shared characters: counts from ../shared/data/README.md (raw / welded / triangles).

struct Character {
  const char* file;
  Index raw, welded, triangles;
};
const Character kCharacters[] = {
    {"CesiumMan.glb", 3273, 2338, 4672},
    {"Fox.glb", 1728, 290, 576},
    {"RiggedFigure.glb", 370, 130, 256},
    {"RiggedSimple.glb", 160, 96, 188},
};

TEST(GltfRead, SharedCharactersHaveTheDocumentedCounts) {
  SKINSLIDE_REQUIRE_GLTF("CesiumMan.glb", "Fox.glb", "RiggedFigure.glb", "RiggedSimple.glb");
  for (const Character& c : kCharacters) {
    SCOPED_TRACE(c.file);
    const MeshFile f = read_gltf_file(shared_gltf(c.file), {});
    EXPECT_EQ(f.format, MeshFormat::Glb);
    ASSERT_TRUE(f.gltf);
    EXPECT_EQ(static_cast<Index>(f.gltf->welded.size()), c.raw);
    EXPECT_EQ(f.mesh.vertex_count(), c.welded);
    EXPECT_EQ(f.mesh.face_count(), c.triangles);
    // Welding is by exact position: every raw vertex sits exactly on its welded vertex, and
    // distinct welded vertices are at distinct positions.
    std::set<std::array<double, 3>> seen;
    for (const Vec3& p : f.mesh.positions) EXPECT_TRUE(seen.insert({p.x(), p.y(), p.z()}).second);
    for (size_t r = 0; r < f.gltf->welded.size(); ++r)
      ASSERT_EQ(f.gltf->raw_positions[r], f.mesh.positions[f.gltf->welded[r]]);
    // The welded surface is closed and manifold (data/README.md): every edge in two triangles,
    // once in each direction.
    std::map<std::pair<Index, Index>, int> directed;
    for (Index t = 0; t < f.mesh.face_count(); ++t)
      for (int k = 0; k < 3; ++k)
        ++directed[{f.mesh.face_begin(t)[k], f.mesh.face_begin(t)[(k + 1) % 3]}];
    for (const auto& [e, n] : directed) {
      EXPECT_EQ(n, 1);
      EXPECT_EQ(directed.count({e.second, e.first}), 1u);
    }
  }
}

TEST(GltfRead, NonIndexedFoxTakesVerticesThreeByThree) {
  SKINSLIDE_REQUIRE_GLTF("Fox.glb");
  const MeshFile f = read_gltf_file(shared_gltf("Fox.glb"), {});
  for (Index t = 0; t < f.mesh.face_count(); ++t)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(f.gltf->triangle_raw[t][k], 3 * t + k);
  EXPECT_EQ(f.gltf->primitives.at(0).normal_accessor, -1);  // no NORMAL: nothing to re-derive
}

// ---------------------------------------------------------------------------------------------
// A hand-built file exercising the reader's paths. Square [0,2]^2 at z = 0 with its centre
// c = (1,1,0), corners v1 (0,0), v2 (2,0), v3 (2,2), v4 (0,2):
//  primitive 0: interleaved float POSITION+NORMAL (byteStride 24), u16 indices, TRIANGLES
//               raw c v1 v2 v3, triangles (c v1 v2) (c v2 v3)
//  primitive 1: KHR_mesh_quantization: POSITION unsigned short (stride 8), NORMAL normalized
//               byte (stride 4); TRIANGLE_FAN without indices over raw c' v3' v4' v1':
//               triangles (v3' v4' c') (v4' v1' c')
//  primitive 2: float POSITION with a sparse substitution: (10,0,0) (11,0,0) (10,1,0), the last
//               replaced by (10,1,5)
//  primitive 3: POINTS over primitive 2's POSITION (not part of the surface)

struct Bytes {
  std::vector<unsigned char> data;
  template <typename T>
  void put(T v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    data.insert(data.end(), b, b + sizeof(T));
  }
  void pad(size_t to) {
    while (data.size() < to) data.push_back(0);
  }
};

const float kNormals0[4][3] = {{0, 0, 1}, {0, -0.6f, 0.8f}, {0.6f, 0, 0.8f}, {0, 0, 1}};

// The JSON with "@BUFFER@" where the buffer's URI goes, and the buffer's bytes.
std::pair<std::string, std::vector<unsigned char>> handmade_parts() {
  Bytes b;
  const float p0[4][3] = {{1, 1, 0}, {0, 0, 0}, {2, 0, 0}, {2, 2, 0}};
  for (int i = 0; i < 4; ++i) {  // bv0: interleaved, 96 bytes
    for (float x : p0[i]) b.put(x);
    for (float x : kNormals0[i]) b.put(x);
  }
  for (std::uint16_t i : {0, 1, 2, 0, 2, 3}) b.put(i);  // bv1 @96: 12 bytes
  const std::uint16_t p1[4][3] = {{1, 1, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 0}};
  for (auto& v : p1) {  // bv2 @108: stride 8
    for (std::uint16_t x : v) b.put(x);
    b.put(std::uint16_t{0});
  }
  const std::int8_t n1[4][3] = {{0, 0, 127}, {0, 0, 127}, {-127, 0, 0}, {0, -127, 0}};
  for (auto& v : n1) {  // bv3 @140: stride 4
    for (std::int8_t x : v) b.put(x);
    b.put(std::int8_t{0});
  }
  for (float x : {10.f, 0.f, 0.f, 11.f, 0.f, 0.f, 10.f, 1.f, 0.f}) b.put(x);  // bv4 @156
  b.put(std::uint8_t{2});                                                     // bv5 @192
  b.pad(196);
  for (float x : {10.f, 1.f, 5.f}) b.put(x);  // bv6 @196
  const std::string json = R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_mesh_quantization"],
  "extensionsRequired": ["KHR_mesh_quantization"],
  "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "name": "square"}],
  "meshes": [{"name": "square", "primitives": [
    {"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "mode": 4},
    {"attributes": {"POSITION": 3, "NORMAL": 4}, "mode": 6},
    {"attributes": {"POSITION": 5}},
    {"attributes": {"POSITION": 5}, "mode": 0}]}],
  "buffers": [{"byteLength": 208, "uri": "@BUFFER@"}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 96, "byteStride": 24, "target": 34962},
    {"buffer": 0, "byteOffset": 96, "byteLength": 12, "target": 34963},
    {"buffer": 0, "byteOffset": 108, "byteLength": 32, "byteStride": 8, "target": 34962},
    {"buffer": 0, "byteOffset": 140, "byteLength": 16, "byteStride": 4, "target": 34962},
    {"buffer": 0, "byteOffset": 156, "byteLength": 36, "target": 34962},
    {"buffer": 0, "byteOffset": 192, "byteLength": 1},
    {"buffer": 0, "byteOffset": 196, "byteLength": 12}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [2, 2, 0]},
    {"bufferView": 0, "byteOffset": 12, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
    {"bufferView": 2, "componentType": 5123, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [2, 2, 0]},
    {"bufferView": 3, "componentType": 5120, "normalized": true, "count": 4, "type": "VEC3"},
    {"bufferView": 4, "componentType": 5126, "count": 3, "type": "VEC3", "min": [10, 0, 0], "max": [11, 1, 5],
     "sparse": {"count": 1, "indices": {"bufferView": 5, "componentType": 5121}, "values": {"bufferView": 6}}}]
})";
  return {json, b.data};
}

std::string handmade_gltf() {
  auto [json, bytes] = handmade_parts();
  return json.replace(json.find("@BUFFER@"), 8,
                      "data:application/octet-stream;base64," + testing::base64(bytes));
}

std::string write_text(const fs::path& path, const std::string& text) {
  write_file_atomic(path.string(), text);
  return path.string();
}

TEST(GltfRead, HandmadeFileDecodesEveryAccessorKind) {
  const fs::path dir = temp_dir();
  const std::string path = write_text(dir / "square.gltf", handmade_gltf());
  SKINSLIDE_EXPECT_VALID_GLTF(std::vector<std::string>{path});
  const MeshFile f = read_gltf_file(path, {});
  EXPECT_EQ(f.format, MeshFormat::Gltf);
  // Welded: c v1 v2 v3 (primitive 0), v4 (primitive 1), then primitive 2's three vertices.
  const Positions3 expected = {{1, 1, 0}, {0, 0, 0},  {2, 0, 0},  {2, 2, 0},
                               {0, 2, 0}, {10, 0, 0}, {11, 0, 0}, {10, 1, 5}};
  EXPECT_EQ(f.mesh.positions, expected);
  const std::vector<Index> welded = {0, 1, 2, 3, 0, 3, 4, 1, 5, 6, 7};
  EXPECT_EQ(f.gltf->welded, welded);
  const std::vector<std::vector<Index>> faces = {
      {0, 1, 2}, {0, 2, 3}, {3, 4, 0}, {4, 1, 0}, {5, 6, 7}};
  ASSERT_EQ(f.mesh.face_count(), 5);
  for (Index t = 0; t < 5; ++t)
    EXPECT_EQ(std::vector<Index>(f.mesh.face_begin(t), f.mesh.face_begin(t) + 3), faces[t]) << t;
  // Normalized bytes: 127 -> 1, -127 -> -1.
  const std::vector<double> n1 = gltf_accessor_values(f.gltf->model, 4, "test");
  EXPECT_EQ(n1, (std::vector<double>{0, 0, 1, 0, 0, 1, -1, 0, 0, 0, -1, 0}));
}

// Welding numbers each position by its first raw copy, joins only exactly equal positions, and
// takes -0 and +0 as one coordinate; checked by hand, then against an ordered map on positions
// with many repeats.
TEST(GltfRead, WeldingJoinsExactlyEqualPositionsInFirstCopyOrder) {
  const Positions3 raw = {
      {1, 2, 3}, {0, 0, 0}, {1, 2, 3}, {-0.0, 0, -0.0}, {1, 2, std::nextafter(3.0, 4.0)},
      {0, 0, 0}};
  EXPECT_EQ(weld_positions(raw), (std::vector<Index>{0, 1, 0, 1, 2, 1}));
  std::mt19937 rng{7};
  std::uniform_int_distribution<int> pick(0, 999);
  Positions3 many;
  for (int i = 0; i < 20000; ++i) {
    const int k = pick(rng);  // 1000 positions, each about 20 times
    many.emplace_back(k % 10 - 4.5, (k / 10) % 10 * 0.1, k / 100 == 0 ? -0.0 : k / 100 * 1e-3);
  }
  std::map<std::array<double, 3>, Index> first;
  std::vector<Index> expected;
  for (const Vec3& p : many) {
    const auto [it, inserted] =
        first.emplace(std::array<double, 3>{p[0], p[1], p[2]}, static_cast<Index>(first.size()));
    expected.push_back(it->second);
  }
  EXPECT_EQ(weld_positions(many), expected);
  EXPECT_TRUE(weld_positions({}).empty());
}

TEST(GltfRead, MeshChoiceByNameOrIndexAndAListWhenAmbiguous) {
  const fs::path dir = temp_dir();
  std::string json = handmade_gltf();
  // A second mesh "extra" (primitive 2 only) instanced by a second node.
  json.replace(
      json.find(R"("meshes": [)"), 11,
      R"("meshes": [{"name": "extra", "primitives": [{"attributes": {"POSITION": 5}}]}, )");
  json.replace(json.find(R"({"mesh": 0, "name": "square"})"), 29,
               R"({"mesh": 1, "name": "square"}, {"mesh": 0})");
  json.replace(json.find(R"("nodes": [0])"), 12, R"("nodes": [0, 1])");
  const std::string path = write_text(dir / "two.gltf", json);
  try {
    read_gltf_file(path, {});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    const std::string m = e.what();
    EXPECT_NE(m.find("--mesh"), std::string::npos) << m;
    EXPECT_NE(m.find("0 \"extra\": 1 primitive(s), 3 vertices"), std::string::npos) << m;
    EXPECT_NE(m.find("1 \"square\": 4 primitive(s), 11 vertices"), std::string::npos) << m;
  }
  EXPECT_EQ(read_gltf_file(path, {"square"}).mesh.vertex_count(), 8);
  EXPECT_EQ(read_gltf_file(path, {"0"}).mesh.vertex_count(), 3);
  EXPECT_EQ(read_gltf_file(path, {"1"}).gltf->mesh, 1);
  EXPECT_THROW(read_gltf_file(path, {"2"}), Error);
  EXPECT_THROW(read_gltf_file(path, {"nose"}), Error);
}

void expect_input_error(const std::string& json, const std::string& fragment) {
  const fs::path dir = temp_dir();
  const std::string path = write_text(dir / "bad.gltf", json);
  try {
    read_gltf_file(path, {});
    ADD_FAILURE() << "expected an error containing: " << fragment;
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind(path, 0), 0u) << "the message starts with the path";
  }
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

TEST(GltfRead, RejectsWhatItCannotHonour) {
  const std::string good = handmade_gltf();
  expect_input_error(
      replaced(
          good, R"("indices": 2, "mode": 4})",
          R"("indices": 2, "mode": 4, "extensions": {"KHR_draco_mesh_compression": {"bufferView": 0, "attributes": {"POSITION": 0}}}})"),
      "mesh 0 primitive 0: is compressed with KHR_draco_mesh_compression");
  expect_input_error(replaced(good, R"({"POSITION": 0, "NORMAL": 1})", R"({"NORMAL": 1})"),
                     "mesh 0 primitive 0: has no POSITION attribute");
  expect_input_error(
      replaced(good, R"("count": 6, "type": "SCALAR")", R"("count": 5, "type": "SCALAR")"),
      "5 triangle-list indices: not a multiple of 3");
  // An index past the vertices: 3 elements in the view read as 4 bytes wide.
  expect_input_error(replaced(good, R"("componentType": 5123, "count": 6)",
                              R"("componentType": 5125, "count": 3)"),
                     "indices accessor 2: index 0 is 65536, past the 4 vertices");
  expect_input_error(
      replaced(good, R"("byteLength": 36, "target")", R"("byteLength": 30, "target")"),
      "POSITION accessor 5: 3 elements from byte 0 run past the end of buffer view 4");
  expect_input_error(
      replaced(good, R"("values": {"bufferView": 6})", R"("values": {"bufferView": 9})"),
      "sparse values buffer view 9 does not exist");
  std::string lines_only =
      replaced(good, R"("indices": 2, "mode": 4})", R"("indices": 2, "mode": 1})");
  lines_only = replaced(lines_only, R"("mode": 6})", R"("mode": 3})");
  lines_only = replaced(lines_only, R"({"attributes": {"POSITION": 5}},)",
                        R"({"attributes": {"POSITION": 5}, "mode": 2},)");
  expect_input_error(lines_only, "mesh 0: has no triangles");
  expect_input_error("{\"asset\": {\"version\": \"2.0\"}}", "the file has no mesh");
  expect_input_error("{not json", "not a readable glTF 2.0 file");
}

TEST(GltfRead, TruncatedGlbIsAnInputErrorAtEveryLength) {
  SKINSLIDE_REQUIRE_GLTF("RiggedSimple.glb");
  const std::string bytes = read_file(shared_gltf("RiggedSimple.glb"));
  const fs::path dir = temp_dir();
  const std::string path = (dir / "cut.glb").string();
  int errors = 0;
  for (size_t n = 0; n < bytes.size(); n += (n < 4000 ? 1 : 61)) {
    write_file_atomic(path, std::string_view(bytes.data(), n));
    try {
      read_gltf_file(path, {});
      ADD_FAILURE() << "a GLB cut to " << n << " of " << bytes.size() << " bytes was accepted";
    } catch (const Error& e) {
      ASSERT_EQ(e.kind(), ErrorKind::Input) << n << ": " << e.what();
      ++errors;
    }
  }
  EXPECT_GT(errors, 4000);
}

// ---------------------------------------------------------------------------------------------
// Writing.

TEST(GltfWrite, RoundTripOfEachCharacterIsTheSameDocument) {
  SKINSLIDE_REQUIRE_GLTF("CesiumMan.glb", "Fox.glb", "RiggedFigure.glb", "RiggedSimple.glb");
  const fs::path dir = temp_dir();
  std::vector<std::string> written;
  for (const Character& c : kCharacters) {
    SCOPED_TRACE(c.file);
    const MeshFile f = read_gltf_file(shared_gltf(c.file), {});
    const std::string glb = (dir / c.file).string();
    write_gltf_file(f, SlidVertices{}, glb);
    const auto r = compare_gltf(shared_gltf(c.file), glb);
    EXPECT_EQ(r.status, 0) << r.output;
    // .glb in, .gltf + .bin out (the CLI keeps the extension; this is the other writer path).
    const std::string gltf = (dir / (fs::path(c.file).stem().string() + ".gltf")).string();
    write_gltf_file(f, SlidVertices{}, gltf);
    EXPECT_TRUE(fs::exists(dir / (fs::path(c.file).stem().string() + ".bin")));
    const auto r2 = compare_gltf(shared_gltf(c.file), gltf);
    EXPECT_EQ(r2.status, 0) << r2.output;
    // Reading the copy gives the same surface.
    const MeshFile again = read_gltf_file(glb, {});
    EXPECT_EQ(again.mesh.positions, f.mesh.positions);
    EXPECT_TRUE(same_faces(again.mesh, f.mesh));
    written.push_back(glb);
    written.push_back(gltf);
  }
  SKINSLIDE_EXPECT_VALID_GLTF(written);
}

TEST(GltfWrite, HandmadeRoundTripKeepsDataUriBuffersAsBinFiles) {
  const fs::path dir = temp_dir();
  const std::string in = write_text(dir / "square.gltf", handmade_gltf());
  fs::create_directories(dir / "out");
  const std::string out = (dir / "out" / "slid.gltf").string();
  write_gltf_file(read_gltf_file(in, {}), SlidVertices{}, out);
  EXPECT_TRUE(fs::exists(dir / "out" / "slid.bin"));
  const auto r = compare_gltf(in, out);
  EXPECT_EQ(r.status, 0) << r.output;
  SKINSLIDE_EXPECT_VALID_GLTF(std::vector<std::string>{out});
}

Vec3 normalised(Vec3 v) { return v / v.norm(); }

TEST(GltfWrite, SlidVertexMovesEveryRawCopyAndGetsInterpolatedNormals) {
  const fs::path dir = temp_dir();
  const std::string in = write_text(dir / "square.gltf", handmade_gltf());
  const MeshFile f = read_gltf_file(in, {});
  // The centre (welded 0; raw copies in primitives 0 and 1) lands in triangle 0 (c v1 v2).
  SlidVertices slid;
  slid.vertex = {0};
  SurfaceSample s;
  s.face = 0;
  s.corner = {0, 1, 2};
  s.weight = {0.5, 0.25, 0.25};
  slid.sample = {s};
  slid.position = {Vec3(1.0, 0.5, 0.0)};  // 0.5 c + 0.25 v1 + 0.25 v2
  for (const char* name : {"slid.gltf", "slid.glb"}) {
    SCOPED_TRACE(name);
    const std::string out = (dir / name).string();
    write_gltf_file(f, slid, out);
    SKINSLIDE_EXPECT_VALID_GLTF(std::vector<std::string>{out});
    const MeshFile g = read_gltf_file(out, {});
    EXPECT_EQ(g.format, std::string(name).ends_with(".glb") ? MeshFormat::Glb : MeshFormat::Gltf);
    Positions3 expected = f.mesh.positions;
    expected[0] = Vec3(1.0, 0.5, 0.0);
    EXPECT_EQ(g.mesh.positions, expected);  // the two raw copies weld again: both moved
    EXPECT_EQ(g.gltf->raw_positions[0], expected[0]);
    EXPECT_EQ(g.gltf->raw_positions[4], expected[0]);
    // Hand-computed normal: normalise(0.5 n(c) + 0.25 n(v1) + 0.25 n(v2)), stored as float.
    const Vec3 n =
        normalised(0.5 * Vec3(0, 0, 1) + 0.25 * Vec3(0, -0.6f, 0.8f) + 0.25 * Vec3(0.6f, 0, 0.8f));
    const auto& model = g.gltf->model;
    const std::vector<double> n0 =
        gltf_accessor_values(model, g.gltf->primitives[0].normal_accessor, "t");
    const std::vector<double> n1 =
        gltf_accessor_values(model, g.gltf->primitives[1].normal_accessor, "t");
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(n0[c], static_cast<float>(n[c]));
      EXPECT_EQ(n1[c], static_cast<float>(n[c]));
    }
    // Untouched vertices keep their normals exactly.
    for (int v = 1; v < 4; ++v)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(n0[3 * v + c], kNormals0[v][c]);
    EXPECT_EQ(std::vector<double>(n1.begin() + 3, n1.end()),
              (std::vector<double>{0, 0, 1, -1, 0, 0, 0, -1, 0}));
    // Primitive 0's float accessor was edited in place; primitive 1's quantized one replaced
    // by a new float accessor, with exact min/max.
    EXPECT_EQ(g.gltf->primitives[0].position_accessor, 0);
    const int q = g.gltf->primitives[1].position_accessor;
    EXPECT_GE(q, 6);
    EXPECT_EQ(model.accessors[q].componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
    EXPECT_EQ(model.accessors[q].minValues, (std::vector<double>{0, 0, 0}));
    EXPECT_EQ(model.accessors[q].maxValues, (std::vector<double>{2, 2, 0}));
    // Everything else is the same document: only the edited accessors' min/max and the new
    // accessors, views and buffer bytes differ.
    const auto r = compare_gltf(in, out, {0, 1});
    EXPECT_NE(r.status, 0);  // the quantized primitive now points at a new accessor
    EXPECT_NE(r.output.find("meshes/0/primitives/1/attributes/POSITION"), std::string::npos)
        << r.output;
  }
}

TEST(GltfWrite, OnlyTheMovedVerticesBytesChangeInACharacter) {
  SKINSLIDE_REQUIRE_GLTF("RiggedSimple.glb");
  const fs::path dir = temp_dir();
  const MeshFile f = read_gltf_file(shared_gltf("RiggedSimple.glb"), {});
  // Move welded vertex 40 to the centroid of a triangle that uses it.
  Index tri = -1;
  for (Index t = 0; t < f.mesh.face_count() && tri < 0; ++t)
    for (int k = 0; k < 3; ++k)
      if (f.mesh.face_begin(t)[k] == 40) tri = t;
  ASSERT_GE(tri, 0);
  SlidVertices slid;
  slid.vertex = {40};
  SurfaceSample s;
  s.face = tri;
  s.weight = {1.0 / 3, 1.0 / 3, 1.0 / 3};
  slid.sample = {s};
  const Index* v = f.mesh.face_begin(tri);
  slid.position = {(f.mesh.positions[v[0]] + f.mesh.positions[v[1]] + f.mesh.positions[v[2]]) / 3};
  const std::string out = (dir / "RiggedSimple.glb").string();
  write_gltf_file(f, slid, out);
  SKINSLIDE_EXPECT_VALID_GLTF(std::vector<std::string>{out});
  const auto r = compare_gltf(shared_gltf("RiggedSimple.glb"), out, {2, 3});
  EXPECT_EQ(r.status, 0) << r.output;  // JSON: only NORMAL (2) and POSITION (3) min/max
  const MeshFile g = read_gltf_file(out, {});
  const auto& a = f.gltf->model.buffers[0].data;
  const auto& b = g.gltf->model.buffers[0].data;
  ASSERT_EQ(a.size(), b.size());
  // The changed bytes all lie in the POSITION/NORMAL elements of the raw copies of vertex 40.
  std::set<size_t> allowed;
  for (size_t raw = 0; raw < f.gltf->welded.size(); ++raw) {
    if (f.gltf->welded[raw] != 40) continue;
    for (int acc :
         {f.gltf->primitives[0].position_accessor, f.gltf->primitives[0].normal_accessor}) {
      const size_t at = gltf_element_offset(f.gltf->model, acc, raw);
      for (size_t k = 0; k < 12; ++k) allowed.insert(at + k);
    }
  }
  int changed = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i] != b[i]) {
      ++changed;
      EXPECT_TRUE(allowed.count(i)) << "byte " << i;
    }
  EXPECT_GT(changed, 0);
  for (size_t raw = 0; raw < f.gltf->welded.size(); ++raw) {
    if (f.gltf->welded[raw] != 40) continue;
    EXPECT_LT((g.gltf->raw_positions[raw] - slid.position[0]).norm(), 1e-6);
  }
}

TEST(GltfWrite, UnwritableTargetIsAnOutputErrorAndLeavesNoFile) {
  SKINSLIDE_REQUIRE_GLTF("RiggedSimple.glb");
  const fs::path dir = temp_dir();
  const MeshFile f = read_gltf_file(shared_gltf("RiggedSimple.glb"), {});
  try {
    write_gltf_file(f, SlidVertices{}, (dir / "missing" / "x.glb").string());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Output);
  }
  EXPECT_TRUE(fs::is_empty(dir));
}

// A 1x1 RGBA PNG.
const std::vector<unsigned char> kPng = {
    0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A, 0x00, 0x00, 0x00, 0x0D, 0x49, 0x48,
    0x44, 0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00,
    0x00, 0x1F, 0x15, 0xC4, 0x89, 0x00, 0x00, 0x00, 0x0A, 0x49, 0x44, 0x41, 0x54, 0x78,
    0x9C, 0x63, 0x00, 0x01, 0x00, 0x00, 0x05, 0x00, 0x01, 0x0D, 0x0A, 0x2D, 0xB4, 0x00,
    0x00, 0x00, 0x00, 0x49, 0x45, 0x4E, 0x44, 0xAE, 0x42, 0x60, 0x82};

TEST(GltfWrite, ExternalBuffersAndImagesStayReachableFromAnotherFolder) {
  const fs::path dir = temp_dir();
  auto [json, bytes] = handmade_parts();
  json.replace(json.find("@BUFFER@"), 8, "square.bin");
  json.replace(
      json.find(R"("scene": 0,)"), 11,
      R"("scene": 0, "images": [{"uri": "tex/skin.png"}, {"uri": "data:image/png;base64,)" +
          testing::base64(kPng) + R"("}],)");
  fs::create_directories(dir / "in" / "tex");
  fs::create_directories(dir / "out");
  write_file_atomic((dir / "in" / "square.bin").string(),
                    std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  write_file_atomic((dir / "in" / "tex" / "skin.png").string(),
                    std::string_view(reinterpret_cast<const char*>(kPng.data()), kPng.size()));
  const std::string in = write_text(dir / "in" / "square.gltf", json);
  SKINSLIDE_EXPECT_VALID_GLTF(std::vector<std::string>{in});
  const std::string out = (dir / "out" / "frame.gltf").string();
  write_gltf_file(read_gltf_file(in, {}), SlidVertices{}, out);
  EXPECT_EQ(read_file((dir / "out" / "frame.bin").string()),
            read_file((dir / "in" / "square.bin").string()));
  const MeshFile g = read_gltf_file(out, {});
  ASSERT_EQ(g.gltf->model.images.size(), 2u);
  EXPECT_EQ(g.gltf->model.images[0].uri, "../in/tex/skin.png");
  EXPECT_EQ(g.gltf->model.images[1].image, kPng);  // the data URI's bytes, not re-encoded
  SKINSLIDE_EXPECT_VALID_GLTF(std::vector<std::string>{out});
  // And as GLB: buffer 0 becomes the BIN chunk, the images keep their URIs.
  const std::string glb = (dir / "out" / "frame.glb").string();
  write_gltf_file(read_gltf_file(in, {}), SlidVertices{}, glb);
  EXPECT_EQ(read_gltf_file(glb, {}).gltf->model.images[0].uri, "../in/tex/skin.png");
  SKINSLIDE_EXPECT_VALID_GLTF(std::vector<std::string>{glb});
}

}  // namespace
}  // namespace skinslide
