#include "join.h"

#include <cstdio>
#include <filesystem>
#include <new>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "skinslide.h"

namespace skinslide {

int run_join(int argc, char** argv) {
  std::vector<std::string> chunks;
  std::string output;
  bool quiet = false;
  CLI::App app{
      "skinslide join: joins the point cache chunks of a shot, written by farm tasks each given "
      "its --frames\n"
      "range (shot.0001-0100.pc2, shot.0101-0200.pc2, ...), into the cache one task sliding "
      "every frame\n"
      "writes (shot.pc2), byte for byte. Chunks may be given in any order; they must be one run "
      "of samples\n"
      "with no gap and no overlap.",
      "skinslide join"};
  app.add_option("chunks", chunks, "Cache chunks, <shot>.<first>-<last>.pc2 or .mdd")
      ->required()
      ->type_name("CHUNK...");
  app.add_option("-o,--output", output,
                 "Folder for the joined cache <shot>.pc2 (default: the first chunk's folder)")
      ->type_name("DIR");
  app.add_flag("-q,--quiet", quiet, "Errors only");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "skinslide join: error: %s\nRun with --help for the options.\n", e.what());
    return exit_code(ErrorKind::Usage);
  }
  try {
    if (output.empty()) {
      output = std::filesystem::path(chunks.front()).parent_path().string();
      if (output.empty()) output = ".";
    }
    const JoinResult joined = join_cache_chunks(chunks, output);
    if (!quiet)
      std::fprintf(stderr, "skinslide join: %zu chunks, %d samples of %d points -> %s\n",
                   joined.chunks, joined.header.samples, joined.header.points,
                   joined.output.c_str());
    return 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "skinslide join: error: %s\n", e.what());
    return exit_code(e.kind());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "skinslide join: error: out of memory\n");
    return exit_code(ErrorKind::Internal);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "skinslide join: internal error: %s\n", e.what());
    return exit_code(ErrorKind::Internal);
  }
}

}  // namespace skinslide
