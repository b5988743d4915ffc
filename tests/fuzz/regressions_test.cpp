// The fuzz targets' inputs as unit tests (run under ASan+UBSan by scripts/test.sh): every seed in
// tests/fuzz/corpus/<target>/ reads, and every input kept in tests/fuzz/regressions/<target>/
// (each once crashed, hung or broke an invariant) either reads or throws skinslide::Error.

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>

#include "core/error.h"
#include "io/atomic_write.h"
#include "io/gltf/gltf.h"
#include "io/obj_read.h"
#include "io/obj_rewrite.h"
#include "io/patch_file.h"
#include "io/point_cache.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

const fs::path kFuzzDir = fs::path(SKINSLIDE_SOURCE_DIR) / "tests" / "fuzz";

using Reader = std::function<void(const std::string& path)>;

void read_obj_checked(const std::string& path) {
  const std::string bytes = read_file(path);
  const ObjMesh obj = parse_obj(path, bytes);
  EXPECT_EQ(rewrite_obj(obj.text, obj.mesh.positions, obj.mesh.positions), bytes) << path;
}

void read_patch_checked(const std::string& path) { selected_faces(read_patch(path), 1000); }

void read_gltf_checked(const std::string& path) { read_gltf_file(path, {}); }

// Every sample too: a cache's coordinates are checked as they are read.
void read_cache_checked(const std::string& path) {
  const CacheReader cache(path);
  for (int k = 0; k < cache.header().samples; ++k) cache.sample(k);
}

// Runs `read` on every file of kFuzzDir/sub/target; returns how many there were.
int each_file(const std::string& sub, const std::string& target, const Reader& read,
              bool must_read) {
  int n = 0;
  const fs::path dir = kFuzzDir / sub / target;
  if (!fs::is_directory(dir)) return 0;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    // A .bin is a buffer a glTF seed names (the gltf target writes the same one beside each input).
    if (!e.is_regular_file() || e.path().filename() == "README.md" ||
        e.path().extension() == ".bin")
      continue;
    ++n;
    SCOPED_TRACE(e.path().string());
    try {
      read(e.path().string());
    } catch (const Error& err) {
      EXPECT_FALSE(must_read) << err.what();
      EXPECT_NE(err.kind(), ErrorKind::Internal) << err.what();
    }
  }
  return n;
}

struct Target {
  const char* name;
  Reader read;
};

const Target kTargets[] = {{"obj", read_obj_checked},
                           {"patch", read_patch_checked},
                           {"gltf", read_gltf_checked},
                           {"pc2", read_cache_checked},
                           {"mdd", read_cache_checked}};

TEST(FuzzInputs, EverySeedReads) {
  for (const Target& t : kTargets)
    EXPECT_GE(each_file("corpus", t.name, t.read, true), 2) << t.name;
}

TEST(FuzzInputs, EveryRegressionReadsOrIsRefused) {
  int n = 0;
  for (const Target& t : kTargets) n += each_file("regressions", t.name, t.read, false);
  EXPECT_GE(n, 4);  // tests/fuzz/regressions/README.md lists them
}

}  // namespace
}  // namespace skinslide
