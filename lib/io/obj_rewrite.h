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
/// Held whole in memory (the tests and the fuzzer read it back); frames are written by
/// write_rewritten_obj.
std::string rewrite_obj(const ObjText& obj, const Positions3& original,
                        const Positions3& positions);

/// The same text written to `path` as it is made (through AtomicFile: complete or not at all),
/// without holding it whole in memory: at 1M vertices that is about 100 MB less per frame.
/// \throw Error(Output) naming `path` when it cannot be written.
void write_rewritten_obj(const std::string& path, const ObjText& obj, const Positions3& original,
                         const Positions3& positions);

}  // namespace skinslide
