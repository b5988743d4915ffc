#include "join.h"

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "exit_status.h"
#include "help_format.h"
#include "skinslide.h"

namespace skinslide {

int run_join(int argc, char** argv) {
  std::vector<std::string> chunks;
  std::string output;
  bool quiet = false;
  CLI::App app{
      "skinslide join: joins the point cache chunks of a shot, written by farm tasks each given "
      "its --frames range (shot.0001-0100.pc2, shot.0101-0200.pc2, ...), into the cache one task "
      "sliding every frame writes (shot.pc2), byte for byte. Chunks may be given in any order; "
      "they must be one run of samples with no gap and no overlap.",
      "skinslide join"};
  cli::use_help_format(app);
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
    return cli::parse_error_exit(app, e, "skinslide join");
  }
  return cli::exit_status("skinslide join", [&] {
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
  });
}

}  // namespace skinslide
