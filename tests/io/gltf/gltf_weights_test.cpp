#include "io/gltf/gltf_weights.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/atomic_write.h"
#include "io/gltf/gltf.h"
#include "io/gltf/gltf_document.h"
#include "io/gltf/gltf_test_util.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;
using testing::temp_dir;

// Two triangles, one a primitive, sharing an edge; both carry _SLIDE_WEIGHT.
//  primitive 0: float POSITION (0,0,0) (1,0,0) (0,1,0), no indices; float weights w0 w1 w2
//  primitive 1: float POSITION (1,0,0) (1,1,0) (0,1,0), no indices; normalized unsigned byte
//               weights 0 51 255 (accessor 3), or normalized unsigned short 0 13107 65535
//               (accessor 4)
//  primitive 2: POINTS over primitive 0's POSITION, without weights (not part of the surface)
// Welded: raw 0 1 2 3 4 5 -> 0 1 2 1 3 2, so raw 3 and 5 are second copies of welded 1 and 2.

template <typename T>
void put(std::vector<unsigned char>& b, T v) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &v, sizeof(T));
  b.insert(b.end(), bytes, bytes + sizeof(T));
}

std::string weighted_gltf(const std::array<float, 3>& w0) {
  std::vector<unsigned char> b;
  for (float x : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(b, x);  // bv0 @0
  for (float x : {1.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 1.f, 0.f}) put(b, x);  // bv1 @36
  for (float x : w0) put(b, x);                                             // bv2 @72
  for (std::uint8_t x : {0, 51, 255}) put(b, x);                            // bv3 @84
  put(b, std::uint8_t{0});
  for (std::uint16_t x : {0, 13107, 65535}) put(b, x);  // bv4 @88
  put(b, std::uint16_t{0});
  return R"({
  "asset": {"version": "2.0"},
  "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"name": "pair", "primitives": [
    {"attributes": {"POSITION": 0, "_SLIDE_WEIGHT": 2}},
    {"attributes": {"POSITION": 1, "_SLIDE_WEIGHT": 3}},
    {"attributes": {"POSITION": 0}, "mode": 0}]}],
  "buffers": [{"byteLength": 96, "uri": "data:application/octet-stream;base64,)" +
         testing::base64(b) + R"("}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 36},
    {"buffer": 0, "byteOffset": 36, "byteLength": 36},
    {"buffer": 0, "byteOffset": 72, "byteLength": 12},
    {"buffer": 0, "byteOffset": 84, "byteLength": 3},
    {"buffer": 0, "byteOffset": 88, "byteLength": 6}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 2, "componentType": 5126, "count": 3, "type": "SCALAR"},
    {"bufferView": 3, "componentType": 5121, "normalized": true, "count": 3, "type": "SCALAR"},
    {"bufferView": 4, "componentType": 5123, "normalized": true, "count": 3, "type": "SCALAR"}]
})";
}

const std::array<float, 3> kWeights0 = {0.25f, 0.5f, 0.75f};

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

MeshFile read_json(const std::string& json) {
  const fs::path path = temp_dir() / "pair.gltf";
  write_file_atomic(path.string(), json);
  return read_gltf_file(path.string(), {});
}

// The Input error's message for weights `name` of `json` ("" when none is thrown).
std::string weights_error(const std::string& json, const std::string& name = "_SLIDE_WEIGHT") {
  const MeshFile f = read_json(json);
  try {
    gltf_attribute_weights(f, name);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind(f.path + ": mesh 0 primitive ", 0), 0u) << e.what();
    return e.what();
  }
  return "";
}

TEST(GltfAttributeWeights, WeldedVerticesTakeTheirFirstRawCopysWeight) {
  const MeshFile f = read_json(weighted_gltf(kWeights0));
  ASSERT_EQ(f.mesh.vertex_count(), 4);
  ASSERT_EQ(f.gltf->welded, (std::vector<Index>{0, 1, 2, 1, 3, 2}));
  // Welded 1 and 2 also have raw copies 3 (weight 0) and 5 (weight 1): their first copies win.
  // Welded 3 is raw 4, the unsigned byte 51.
  EXPECT_EQ(gltf_attribute_weights(f, "_SLIDE_WEIGHT"),
            (std::vector<double>{0.25, 0.5, 0.75, 0.2}));
}

TEST(GltfAttributeWeights, NormalizedUnsignedShortsAndSparseFloats) {
  std::string json =
      replaced(weighted_gltf(kWeights0), R"("_SLIDE_WEIGHT": 3)", R"("_SLIDE_WEIGHT": 4)");
  EXPECT_EQ(gltf_attribute_weights(read_json(json), "_SLIDE_WEIGHT"),
            (std::vector<double>{0.25, 0.5, 0.75, 0.2}));
  // Primitive 0's weights as a sparse accessor over zeros: one substitution, at the index in
  // the first byte of bv 3 (0), of the value in the first float of bv 2 (0.25).
  json = replaced(json, R"({"bufferView": 2, "componentType": 5126, "count": 3, "type": "SCALAR"})",
                  R"({"componentType": 5126, "count": 3, "type": "SCALAR", "sparse": {"count": 1,
                      "indices": {"bufferView": 3, "componentType": 5121},
                      "values": {"bufferView": 2}}})");
  EXPECT_EQ(gltf_attribute_weights(read_json(json), "_SLIDE_WEIGHT"),
            (std::vector<double>{0.25, 0, 0, 0.2}));
}

TEST(GltfAttributeWeights, EveryTrianglePrimitiveNeedsTheAttribute) {
  const std::string good = weighted_gltf(kWeights0);
  std::string m =
      weights_error(replaced(good, R"({"POSITION": 1, "_SLIDE_WEIGHT": 3})", R"({"POSITION": 1})"));
  EXPECT_NE(m.find("pair.gltf: mesh 0 primitive 1: has no _SLIDE_WEIGHT attribute"),
            std::string::npos)
      << m;
  m = weights_error(good, "_PAINT");
  EXPECT_NE(m.find("mesh 0 primitive 0: has no _PAINT attribute"), std::string::npos) << m;
}

TEST(GltfAttributeWeights, RejectsOtherTypesCountsAndValues) {
  const std::string good = weighted_gltf(kWeights0);
  std::string m = weights_error(replaced(good, R"(5121, "normalized": true)", R"(5121)"));
  EXPECT_NE(m.find("primitive 1: _SLIDE_WEIGHT accessor 3: is SCALAR unsigned byte; slide weights "
                   "need SCALAR float, normalized unsigned byte or normalized unsigned short"),
            std::string::npos)
      << m;
  m = weights_error(
      replaced(good, R"("count": 3, "type": "SCALAR"})", R"("count": 1, "type": "VEC3"})"));
  EXPECT_NE(m.find("primitive 0: _SLIDE_WEIGHT accessor 2: is VEC3 float"), std::string::npos) << m;
  m = weights_error(
      replaced(good, R"("count": 3, "type": "SCALAR"})", R"("count": 2, "type": "SCALAR"})"));
  EXPECT_NE(m.find("accessor 2: has 2 elements, POSITION has 3"), std::string::npos) << m;
  m = weights_error(good, "POSITION");
  EXPECT_NE(m.find("POSITION accessor 0: is VEC3 float"), std::string::npos) << m;

  m = weights_error(weighted_gltf({0.25f, 1.5f, 0.75f}));
  EXPECT_NE(m.find("primitive 0: _SLIDE_WEIGHT accessor 2: element 1 is 1.5, outside [0, 1]"),
            std::string::npos)
      << m;
  m = weights_error(weighted_gltf({0.25f, 0.5f, -0.25f}));
  EXPECT_NE(m.find("element 2 is -0.25, outside [0, 1]"), std::string::npos) << m;
  m = weights_error(weighted_gltf({std::numeric_limits<float>::quiet_NaN(), 0.5f, 0.75f}));
  EXPECT_NE(m.find("element 0 is not finite"), std::string::npos) << m;
  m = weights_error(weighted_gltf({0.25f, std::numeric_limits<float>::infinity(), 0.75f}));
  EXPECT_NE(m.find("element 1 is not finite"), std::string::npos) << m;
  // The edges of the range are weights.
  EXPECT_EQ(gltf_attribute_weights(read_json(weighted_gltf({0, 1, 0})), "_SLIDE_WEIGHT"),
            (std::vector<double>{0, 1, 0, 0.2}));
}

TEST(GltfAttributeWeights, AnObjFileIsAUsageError) {
  MeshFile obj;
  obj.path = "bind.obj";
  try {
    gltf_attribute_weights(obj, "_SLIDE_WEIGHT");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("bind.obj: "), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace skinslide
