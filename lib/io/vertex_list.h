// Per-vertex control files: slide weights (`--weights`), pinned vertices (`--pin`), and slide
// weights from the colours of an OBJ's `v` lines.
#pragma once

#include <string>
#include <vector>

#include "core/types.h"

namespace skinslide {

struct ObjText;  // io/obj_read.h

/// Parses a slide-weight file for a mesh of `vertex_count` vertices; `#` starts a comment, blank
/// lines are skipped, numbers are separated by whitespace or commas. Two layouts, told apart by
/// the first line that holds numbers:
///  - one weight a line, in vertex order: exactly `vertex_count` lines;
///  - `index weight` pairs (0-based vertex ids, any order): vertices not listed weigh 0, so the
///    file says where skin slides, as a painted mask exported as its non-zero entries does.
/// Output: #V weights, each in [0, 1].
/// \throw Error(Input) "path:line: what" for a token that is not a number, a weight outside
///        [0, 1] or not finite, an id out of range or listed twice, a line of the other layout,
///        the wrong number of lines (dense layout), a file with no weights.
std::vector<double> parse_weights(const std::string& path, const std::string& text,
                                  Index vertex_count);

/// Reads and parses a slide-weight file (see parse_weights).
std::vector<double> read_weights(const std::string& path, Index vertex_count);

/// Parses a vertex-id list (`--pin`), the syntax of patch files for vertices: ids `12`, inclusive
/// ranges `12-40`, Maya component strings `pBody.vtx[12:40]`; whitespace or commas between
/// tokens, `#` comments. Output: ascending distinct 0-based ids (may be empty).
/// \throw Error(Input) "path:line: what" for an unknown token, a backward range, an id past the
///        last vertex.
std::vector<Index> parse_vertex_list(const std::string& path, const std::string& text,
                                     Index vertex_count);

/// Reads and parses a vertex-id list file (see parse_vertex_list).
std::vector<Index> read_vertex_list(const std::string& path, Index vertex_count);

/// Slide weights from OBJ vertex colours `v x y z r g b` or `v x y z r g b a`: channel 0, 1 or 2
/// (r, g, b) of every vertex; an alpha is ignored. \param path used in messages.
/// \throw Error(Input) "path:line: what" for a `v` line without three or four colour numbers
///        after x y z, or a colour (r, g or b, the channel read) outside [0, 1].
std::vector<double> obj_color_weights(const std::string& path, const ObjText& obj, int channel);

}  // namespace skinslide
