// A copy of an OBJ's text with some vertices' coordinates replaced, every other byte kept.
#pragma once

#include <string>

#include "core/types.h"
#include "io/obj_read.h"

namespace skinslide {

/// The text of `obj` with the x y z tokens of every vertex whose position in `positions`
/// differs from `original` replaced by the shortest round-trip text of the new value.
/// Spacing, extra numbers (w, colours), comments, other statements and line endings are kept,
/// so a diff shows only what moved. \pre positions.size() == original.size() == vertex count.
std::string rewrite_obj(const ObjText& obj, const Positions3& original,
                        const Positions3& positions);

}  // namespace skinslide
