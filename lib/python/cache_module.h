// The Python module's point cache functions (skinslide.write_cache, skinslide.read_cache), kept
// apart from the slide's bindings in skinslide_module.cpp.
#pragma once

#include <pybind11/pybind11.h>

namespace skinslide {

/// Adds write_cache and read_cache (io/point_cache.h on numpy arrays) to the module `m`.
void add_cache_functions(pybind11::module_& m);

}  // namespace skinslide
