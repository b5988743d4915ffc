// `skinslide join`: a farm's point cache chunks into the whole shot's cache (io/cache_chunks.h).
#pragma once

namespace skinslide {

/// Runs `join [-o DIR] CHUNK...` (argv[0] is "join"), printing to stderr; returns the exit code
/// (README "Exit codes").
int run_join(int argc, char** argv);

}  // namespace skinslide
