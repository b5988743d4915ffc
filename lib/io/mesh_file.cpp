#include "io/mesh_file.h"

#include <algorithm>

#include "core/error.h"

namespace skinslide {

std::string MeshFile::where_face(Index face) const {
  if (face >= 0 && static_cast<size_t>(face) < face_lines.size())
    return path + ":" + std::to_string(face_lines[face]);
  return path + ": triangle " + std::to_string(face);
}

void require_same_topology(const MeshFile& bind, const MeshFile& frame) {
  const PolyMesh& a = bind.mesh;
  const PolyMesh& b = frame.mesh;
  if (a.vertex_count() != b.vertex_count())
    throw_input(frame.path, 0,
                "has " + std::to_string(b.vertex_count()) + " vertices; the bind (" + bind.path +
                    ") has " + std::to_string(a.vertex_count()) +
                    ": a frame must be the bind mesh deformed");
  if (const Index f = first_differing_face(a, b); f >= 0)
    throw Error(ErrorKind::Input, frame.where_face(f) + ": face " + std::to_string(f) +
                                      " differs from the bind's (" + bind.where_face(f) +
                                      "): a frame must have the bind's faces");
  if (a.face_count() != b.face_count())
    throw_input(frame.path, 0,
                "has " + std::to_string(b.face_count()) + " faces; the bind (" + bind.path +
                    ") has " + std::to_string(a.face_count()));
}

void release_faces(MeshFile& frame) {
  PolyMesh& m = frame.mesh;
  std::vector<Index>{0}.swap(m.face_start);
  std::vector<Index>().swap(m.face_vertices);
  std::vector<long>().swap(frame.face_lines);
}

}  // namespace skinslide
