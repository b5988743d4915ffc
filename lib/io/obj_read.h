// Wavefront OBJ reading: `v` and `f` statements, with where each came from in the text.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/poly_mesh.h"

namespace skinslide {

/// The text of an OBJ file and the byte spans of every vertex's x, y, z tokens, so that a copy
/// with some `v` lines changed can be written with every other byte kept (obj_rewrite.h).
struct ObjText {
  std::string bytes;
  /// Per vertex: [begin, end) byte offsets of the x, y and z tokens: {xb, xe, yb, ye, zb, ze}.
  std::vector<std::array<std::uint64_t, 6>> coordinate_spans;
};

struct ObjMesh {
  PolyMesh mesh;
  std::vector<long> face_lines;    ///< 1-based source line of each face
  std::vector<long> vertex_lines;  ///< 1-based source line of each vertex
  ObjText text;
};

/// Parses OBJ text. Only `v` (first three numbers; a 4th w and colours are kept but ignored) and
/// `f` (first field of each `v/vt/vn` entry; 1-based, negative = relative to the vertices so far;
/// forward references allowed) matter; other statements are kept as text. `#` starts a comment.
/// \param path used in messages only.
/// \throw Error(Input) "path:line: what" for: non-numeric, missing or non-finite coordinates,
///        face index 0 or out of range, faces with fewer than 3 or repeated vertices, binary data,
///        line continuations, a file with no vertices.
ObjMesh parse_obj(const std::string& path, std::string bytes);

/// Reads and parses an OBJ file (see parse_obj).
ObjMesh read_obj(const std::string& path);

}  // namespace skinslide
