// Patch files: which faces of the bind mesh slide.
#pragma once

#include <string>
#include <vector>

#include "core/types.h"

namespace skinslide {

/// One run of faces named in a patch file, first..last inclusive, with where it was written.
struct FaceRange {
  long long first = 0;
  long long last = 0;
  long line = 0;  ///< 1-based line in the patch file
};

/// A parsed patch file. Face ids are 0-based indices into the bind mesh's face order (OBJ: `f`
/// lines in file order; glTF: triangles in primitive order).
struct PatchSelection {
  std::string path;
  std::vector<FaceRange> ranges;
  std::string object;  ///< object named by Maya-style tokens (`pBody.f[1:4]`), empty if none
};

/// Parses patch text. Tokens are separated by whitespace or commas; `#` starts a comment.
/// A token is a face id `12`, an inclusive range `12-40`, or a Maya component string
/// `pBody.f[12:40]` / `pBody.f[12]` (the object name optional: `f[3]`).
/// \throw Error(Input) "path:line: ..." for an unknown token, a reversed range, a negative id,
///        or Maya tokens naming two different objects.
PatchSelection parse_patch(const std::string& path, const std::string& text);

/// Reads and parses a patch file (see parse_patch).
PatchSelection read_patch(const std::string& path);

/// The selected face ids, ascending and without duplicates.
/// \throw Error(Input) "path:line: face 812 is out of range (the bind has 800 faces)" and for an
///        empty selection.
std::vector<Index> selected_faces(const PatchSelection& selection, Index face_count);

}  // namespace skinslide
