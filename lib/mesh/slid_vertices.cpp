#include "mesh/slid_vertices.h"

#include "core/check.h"
#include "core/error.h"

namespace skinslide {

Vec3 surface_point(const PolyMesh& mesh, const Positions3& positions, const SurfaceSample& sample) {
  const Index* fv = mesh.face_begin(sample.face);
  Vec3 p = Vec3::Zero();
  for (int k = 0; k < 3; ++k) p += sample.weight[k] * positions[fv[sample.corner[k]]];
  if (!p.allFinite())
    throw Error(ErrorKind::Numeric,
                "a slid position is not finite (face " + std::to_string(sample.face) + ")");
  return p;
}

Positions3 apply_slide(const Positions3& frame, const SlidVertices& slid) {
  SKINSLIDE_CHECK(slid.vertex.size() == slid.position.size(), "one position per slid vertex");
  Positions3 out = frame;
  for (size_t k = 0; k < slid.vertex.size(); ++k) out[slid.vertex[k]] = slid.position[k];
  return out;
}

}  // namespace skinslide
