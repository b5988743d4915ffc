// skinslide: skin sliding after any deformer (Yang & Zhang 2010), a batch command.
// The command line only: CLI11 options (command_line.h) -> RunOptions -> run() (pipeline/run.h,
// which reads the bind and the patches once, then slides every frame) -> exit code. What the run
// tells goes to stderr here: a line per frame in frame order, or a progress line on a terminal.

#include <unistd.h>

#include <clocale>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command_line.h"
#include "core/allocator.h"
#include "core/error.h"
#include "core/number_format.h"
#include "core/version.h"
#include "compare.h"
#include "exit_status.h"
#include "help_format.h"
#include "io/run_inputs.h"
#include "join.h"
#include "skinslide.h"
#include "progress.h"

using namespace skinslide;

namespace {

// Runs the pipeline, printing what it tells to stderr as -q/-v ask; returns the exit code.
int run_and_print(const cli::CliOptions& o) {
  const cli::Verbosity verbosity =
      o.quiet ? cli::Verbosity::Quiet
              : (o.verbose ? cli::Verbosity::Verbose : cli::Verbosity::Normal);
  const auto shown = [&](LogLevel level) {
    return level == LogLevel::Error || level == LogLevel::Warning ||
           (level == LogLevel::Info && verbosity != cli::Verbosity::Quiet) ||
           verbosity == cli::Verbosity::Verbose;
  };
  std::optional<cli::Progress> progress;
  RunEvents events;
  events.log = [&](const LogLine& line) {
    if (shown(line.level)) std::fprintf(stderr, "%s\n", line.text.c_str());
  };
  events.frames_begin = [&](size_t count) {
    progress.emplace(count, verbosity, isatty(STDERR_FILENO) != 0);
  };
  events.frame_done = [&](size_t j, std::vector<LogLine> lines) {
    std::vector<std::string> text;
    for (LogLine& line : lines)
      if (shown(line.level)) text.push_back(std::move(line.text));
    progress->done(j, std::move(text));
  };
  events.frames_end = [&] { progress->finish(); };
  const RunResult result = skinslide::run(cli::run_options(o), events);
  const size_t failed = result.failures.size();
  std::string counts;
  if (result.not_converged) counts += std::to_string(result.not_converged) + " not converged";
  // A window that costs frames much energy is told with what to do about it, once.
  if (result.window_costly)
    counts += (counts.empty() ? "" : "; ") + std::to_string(result.window_costly) +
              " whose --window mean costs ten points of energy or more, 'X% without the window' on "
              "their lines: try a smaller --window" +
              (o.words.at(window_ends_option().name) == "cycle"
                   ? std::string(", --window-ends one-sided if the shot is not a loop")
                   : std::string(", --window-ends cycle for a loop")) +
              ", or no window for separate poses";
  if (!counts.empty()) counts = " (" + counts + ")";
  if (verbosity != cli::Verbosity::Quiet || failed > 0)
    std::fprintf(stderr, "skinslide: %s %s%s%s in %.2f s -> %s\n",
                 counted(result.frames - failed, "frame", "frames").c_str(),
                 o.no_slide ? "copied" : "slid", counts.c_str(),
                 failed ? (", " + std::to_string(failed) + " failed").c_str() : "",
                 progress->elapsed_seconds(), o.output.c_str());
  return failed ? exit_code(result.failures.front().kind()) : 0;
}

}  // namespace

int main(int argc, char** argv) {
  skinslide::restart_with_huge_pages(argv);
  std::setlocale(LC_ALL, "C");
  skinslide::keep_freed_memory();
  // A farm cancels a task with SIGTERM: no temporary file is left behind (io/atomic_write.h).
  skinslide::remove_temporaries_on_termination();
  // `skinslide join ...`: a farm's cache chunks into the shot's cache (cli/join.cpp).
  if (argc > 1 && std::string(argv[1]) == "join") return run_join(argc - 1, argv + 1);
  // `skinslide compare A B`: two slid outputs compared as meshes, for CI (cli/compare.cpp).
  if (argc > 1 && std::string(argv[1]) == "compare") return run_compare(argc - 1, argv + 1);
  cli::CliOptions o;
  CLI::App app{cli::description(), "skinslide"};
  cli::use_help_format(app);
  cli::add_options(app, o);
  try {
    cli::parse(app, o, argc, argv);
  } catch (const CLI::ParseError& e) {
    return cli::parse_error_exit(app, e, "skinslide");
  }
  // The --config file is an input too: no output may replace it (io/run_inputs.h).
  const skinslide::InputScope inputs;
  if (const CLI::Option* config = app.get_config_ptr(); config && config->count() > 0)
    skinslide::note_input(config->results().front());
  return cli::exit_status("skinslide", [&] { return run_and_print(o); });
}
