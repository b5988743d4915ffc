// A polygon mesh as plain arrays: what every reader produces and every algorithm consumes.
#pragma once

#include <algorithm>
#include <vector>

#include "core/types.h"

namespace skinslide {

/// Vertices and polygonal faces. Faces are stored CSR-style: face f has the vertex ids
/// face_vertices[face_start[f] .. face_start[f+1]), in the file's winding order. Indices are
/// 0-based, in file order (OBJ `v`/`f` order; glTF: welded vertices, triangles in primitive order).
struct PolyMesh {
  Positions3 positions;              ///< #V
  std::vector<Index> face_start{0};  ///< #F + 1
  std::vector<Index> face_vertices;  ///< sum of face sizes

  Index vertex_count() const { return static_cast<Index>(positions.size()); }
  Index face_count() const { return static_cast<Index>(face_start.size()) - 1; }
  Index face_size(Index f) const { return face_start[f + 1] - face_start[f]; }
  const Index* face_begin(Index f) const { return face_vertices.data() + face_start[f]; }
  void add_face(const std::vector<Index>& vertices) {
    face_vertices.insert(face_vertices.end(), vertices.begin(), vertices.end());
    face_start.push_back(static_cast<Index>(face_vertices.size()));
  }
};

/// True when both meshes have the same faces (same sizes, same vertex ids in the same order).
inline bool same_faces(const PolyMesh& a, const PolyMesh& b) {
  return a.face_start == b.face_start && a.face_vertices == b.face_vertices;
}

/// The first face, of those both meshes have, whose size or vertex ids differ; -1 when none does
/// (the face counts may still differ).
inline Index first_differing_face(const PolyMesh& a, const PolyMesh& b) {
  const Index n = std::min(a.face_count(), b.face_count());
  for (Index f = 0; f < n; ++f)
    if (a.face_size(f) != b.face_size(f) ||
        !std::equal(a.face_begin(f), a.face_begin(f) + a.face_size(f), b.face_begin(f)))
      return f;
  return -1;
}

}  // namespace skinslide
