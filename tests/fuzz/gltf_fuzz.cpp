// libFuzzer target: the glTF/GLB reading path (tinygltf, accessor decoding, welding).
// The reader takes a path (external buffers resolve next to it), so each input is written to a
// file in a private temporary folder first. Any input either reads or throws skinslide::Error;
// a mesh read has every face index in range and finite positions.

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "io/gltf.h"

using namespace skinslide;

namespace {

void require(bool cond) {
  if (!cond) std::abort();
}

const std::string& input_path() {
  static const std::string path = [] {
    std::string dir =
        (std::filesystem::temp_directory_path() / "skinslide_fuzz_gltf.XXXXXX").string();
    require(mkdtemp(dir.data()) != nullptr);
    return dir + "/input.gltf";
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = input_path();
  std::FILE* f = std::fopen(path.c_str(), "wb");
  require(f != nullptr);
  require(std::fwrite(data, 1, size, f) == size || size == 0);
  require(std::fclose(f) == 0);
  try {
    const MeshFile m = read_gltf_file(path, {});
    require(m.mesh.face_count() > 0);
    for (Index v : m.mesh.face_vertices) require(v >= 0 && v < m.mesh.vertex_count());
    for (const Vec3& p : m.mesh.positions)
      require(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
  } catch (const Error& e) {
    require(e.kind() == ErrorKind::Input);
  }
  return 0;
}
