// The figures both methods give a patch in the report (its counts and its loops), which each
// method interleaves with its own (elastic/elastic_method.h, paper/paper_method.h).
#pragma once

#include "core/figures.h"
#include "mesh/patch.h"

namespace skinslide {

/// faces, vertices, free, pinned.
Figures patch_counts(const Patch& patch);

/// loops, outer_loop_start (a mesh vertex id), outer_loop_chosen.
Figures patch_loops(const Patch& patch);

}  // namespace skinslide
