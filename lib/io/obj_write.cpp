#include "io/obj_write.h"

#include "core/check.h"
#include "core/number_format.h"

namespace skinslide {

std::string obj_text(const PolyMesh& mesh, const Positions3& positions, const std::string& source) {
  SKINSLIDE_CHECK(static_cast<Index>(positions.size()) == mesh.vertex_count(),
                  "one position per vertex");
  std::string s = "# skinslide: " + source + "\n";
  // Appended piece by piece: no temporary string per number.
  for (const Vec3& p : positions) {
    s += 'v';
    for (int k = 0; k < 3; ++k) {
      s += ' ';
      s += double_text(p[k]).view();
    }
    s += '\n';
  }
  for (Index f = 0; f < mesh.face_count(); ++f) {
    s += 'f';
    for (Index k = 0; k < mesh.face_size(f); ++k) {
      s += ' ';
      s += std::to_string(mesh.face_begin(f)[k] + 1);
    }
    s += '\n';
  }
  return s;
}

}  // namespace skinslide
