// `skinslide compare`: two slid outputs compared as meshes (compare/compare_outputs.h).
#pragma once

namespace skinslide {

/// Runs `compare [options] A B` (argv[0] is "compare"), printing to stderr; returns the exit
/// code: 0 the same within the tolerance, 1 different, 2 usage, 3 bad input, 4 cannot write the
/// report (README "Tests"; an internal error is 1 too, its message says so).
int run_compare(int argc, char** argv);

}  // namespace skinslide
