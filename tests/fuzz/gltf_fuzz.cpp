// libFuzzer target: the glTF/GLB reading path (buffer URI rule, tinygltf, accessor decoding,
// welding). The reader takes a path (external buffers resolve next to it), so each input is
// written to a file in a private temporary folder first: asset/input.gltf, beside it
// asset/inside.bin (one triangle's positions, 36 bytes), and outside it secret.bin (36 bytes too,
// so that a read reaching it would succeed) and a symbolic link asset/up -> the private folder.
// Any input either reads or throws skinslide::Error; a mesh read has every face index in range,
// finite positions, and was read from no file outside asset/ (io/gltf/gltf_uri.h).

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "io/gltf/gltf.h"
#include "io/gltf/gltf_document.h"

using namespace skinslide;

namespace {

namespace fs = std::filesystem;

void require(bool cond) {
  if (!cond) std::abort();
}

void write_file(const fs::path& path, const std::string& bytes) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  require(f != nullptr);
  require(std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size() || bytes.empty());
  require(std::fclose(f) == 0);
}

struct Folder {
  std::string input;
  std::string asset;  // resolved, with a trailing /
};

const Folder& folder() {
  static const Folder f = [] {
    std::string dir = (fs::temp_directory_path() / "skinslide_fuzz_gltf.XXXXXX").string();
    require(mkdtemp(dir.data()) != nullptr);
    const fs::path root = fs::canonical(dir);
    fs::create_directory(root / "asset");
    const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    write_file(root / "asset" / "inside.bin",
               std::string(reinterpret_cast<const char*>(triangle), sizeof triangle));
    write_file(root / "secret.bin", std::string(36, 'S'));
    fs::create_directory_symlink(root, root / "asset" / "up");
    return Folder{(root / "asset" / "input.gltf").string(), (root / "asset").string() + "/"};
  }();
  return f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const Folder& dir = folder();
  write_file(dir.input, std::string(reinterpret_cast<const char*>(data), size));
  try {
    const MeshFile m = read_gltf_file(dir.input, {});
    require(m.mesh.face_count() > 0);
    for (Index v : m.mesh.face_vertices) require(v >= 0 && v < m.mesh.vertex_count());
    for (const Vec3& p : m.mesh.positions)
      require(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
    for (const std::string& file : m.gltf->files_read)
      require(file.compare(0, dir.asset.size(), dir.asset) == 0);
  } catch (const Error& e) {
    require(e.kind() == ErrorKind::Input);
  }
  return 0;
}
