#include "helpers/meshes.h"

#include "helpers/shared_data.h"
#include "helpers/temp_dir.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

namespace skinslide::test {

PolyMesh quad_grid(int n, int m) { return quad_grid_with_holes(n, m, {}); }

PolyMesh quad_grid_with_holes(int n, int m, const std::vector<Index>& holes) {
  PolyMesh mesh;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= n; ++i) mesh.positions.emplace_back(i, j, 0);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const Index f = j * n + i;
      if (std::find(holes.begin(), holes.end(), f) != holes.end()) continue;
      const Index a = j * (n + 1) + i;
      mesh.add_face({a, a + 1, a + n + 2, a + n + 1});
    }
  return mesh;
}

PolyMesh tube(int around, int along, double length) {
  PolyMesh mesh;
  for (int k = 0; k <= along; ++k)
    for (int i = 0; i < around; ++i) {
      const double t = 2 * M_PI * i / around;
      mesh.positions.emplace_back(std::cos(t), std::sin(t), length * k / along);
    }
  for (int k = 0; k < along; ++k)
    for (int i = 0; i < around; ++i) {
      const Index i1 = (i + 1) % around;
      mesh.add_face({k * around + i, k * around + i1, (k + 1) * around + i1, (k + 1) * around + i});
    }
  return mesh;
}

std::vector<Index> all_faces(const PolyMesh& mesh) {
  std::vector<Index> f(mesh.face_count());
  for (Index i = 0; i < mesh.face_count(); ++i) f[i] = i;
  return f;
}

std::string temp_dir(const std::string& name) {
  namespace fs = std::filesystem;
  // Inside the process's folder, removed when the test process exits (helpers/temp_dir.h).
  const fs::path dir = process_temp_dir() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

std::string source_path(const std::string& relative) {
  return std::string(SKINSLIDE_SOURCE_DIR) + "/" + relative;
}

std::string shared_path(const std::string& relative) { return shared_dir() + "/" + relative; }

}  // namespace skinslide::test
