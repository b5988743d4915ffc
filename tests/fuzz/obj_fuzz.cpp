// libFuzzer target: the OBJ reader and the byte-preserving rewrite.
// Any input either parses or throws skinslide::Error; a parsed mesh has every face index in
// range, finite positions and coordinate spans inside the text; rewriting it with nothing moved
// gives the input back byte for byte, and with every vertex moved reads back exactly.

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/error.h"
#include "io/obj_read.h"
#include "io/obj_rewrite.h"

using namespace skinslide;

namespace {

void require(bool cond) {
  if (!cond) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  ObjMesh obj;
  try {
    obj = parse_obj("fuzz.obj", bytes);
  } catch (const Error& e) {
    require(e.kind() == ErrorKind::Input);
    return 0;
  }
  const PolyMesh& m = obj.mesh;
  require(m.vertex_count() > 0);
  require(obj.text.coordinate_spans.size() == m.positions.size());
  require(obj.face_lines.size() == static_cast<size_t>(m.face_count()));
  for (Index f = 0; f < m.face_count(); ++f) {
    require(m.face_size(f) >= 3);
    for (Index k = 0; k < m.face_size(f); ++k)
      require(m.face_begin(f)[k] >= 0 && m.face_begin(f)[k] < m.vertex_count());
  }
  for (size_t v = 0; v < m.positions.size(); ++v) {
    const auto span = coordinate_tokens(obj.text, v);
    require(span[0] == obj.text.coordinate_spans[v][0] &&
            span[5] == obj.text.coordinate_spans[v][1]);
    for (int k = 0; k < 6; k += 2) require(span[k] < span[k + 1] && span[k + 1] <= bytes.size());
  }
  for (const Vec3& p : m.positions)
    require(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));

  require(rewrite_obj(obj.text, m.positions, m.positions) == bytes);

  Positions3 moved = m.positions;
  for (Vec3& p : moved) p = Vec3(p[0] * 0.5 + 1, -p[1], p[2] + 0.25);
  const ObjMesh back = parse_obj("fuzz.obj", rewrite_obj(obj.text, m.positions, moved));
  require(back.mesh.positions.size() == moved.size());
  for (size_t i = 0; i < moved.size(); ++i) require(back.mesh.positions[i] == moved[i]);
  require(same_faces(back.mesh, m));
  return 0;
}
