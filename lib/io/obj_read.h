// Wavefront OBJ reading: `v` and `f` statements, with where each came from in the text.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/poly_mesh.h"

namespace skinslide {

/// The text of an OBJ file and where every vertex's x, y, z tokens are, so that a copy with some
/// `v` lines changed can be written with every other byte kept (obj_rewrite.h).
struct ObjText {
  std::string bytes;
  /// Per vertex: [begin, end) byte offsets from the first byte of its x token to the end of its z
  /// token, the spaces between them included (coordinate_tokens() splits it again). A frame in
  /// flight keeps these: two offsets a vertex instead of six is 31 MB less at 1M vertices.
  std::vector<std::array<std::uint64_t, 2>> coordinate_spans;
};

/// Vertex v's x, y and z tokens as [begin, end) byte offsets: {xb, xe, yb, ye, zb, ze}.
/// \pre v < text.coordinate_spans.size()
std::array<std::uint64_t, 6> coordinate_tokens(const ObjText& text, size_t v);

struct ObjMesh {
  PolyMesh mesh;
  std::vector<long> face_lines;  ///< 1-based source line of each face
  ObjText text;
};

/// Parses OBJ text. Only `v` (first three numbers; up to 4 more, a w or a colour r g b [a], are
/// kept in the text but ignored) and `f` (first field of each `v/vt/vn` entry; 1-based,
/// negative = relative to the vertices so far; forward references allowed) matter; other
/// statements are kept as text. `#` starts a comment. A corner's vt and vn parts are checked
/// (empty, or a whole number but 0) but not read: they need not name an existing vt or vn.
/// \param path used in messages only.
/// \throw Error(Input) "path:line: what" for: non-numeric, missing or non-finite coordinates
///        (a number nearer 0 than the smallest subnormal reads as 0), more than 4 numbers or
///        anything but a number after them, a face corner of more than 3 parts (v/vt/vn/x),
///        a corner's vt or vn part that is not a whole number or is 0, face index 0 or out of
///        range, faces with fewer than 3 or repeated vertices, binary data, line continuations,
///        a file with no vertices.
ObjMesh parse_obj(const std::string& path, std::string bytes);

/// Reads and parses an OBJ file (see parse_obj).
ObjMesh read_obj(const std::string& path);

}  // namespace skinslide
