// A file's format by the end of its name, whatever its case: `.OBJ` is an OBJ.
#pragma once

#include <string>

namespace skinslide {

/// The extension of `path`'s file name, dot included, lower-cased (ASCII): "a/B.GLB" -> ".glb";
/// "" when the name has none.
std::string lower_extension(const std::string& path);

}  // namespace skinslide
