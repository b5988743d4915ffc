// The command line's options (README "Options"): declared for CLI11, checked, and turned into
// the pipeline's RunOptions. Every default is the library's own (RunOptions, ElasticOptions,
// PaperOptions): the options are bound straight into those structs, and --help shows them.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "skinslide.h"

namespace skinslide::cli {

// The command line's options: bound straight into the library's structs, so their defaults are
// the library's; the enums as the words the options take.
struct CliOptions {
  RunOptions run;
  ElasticOptions elastic;
  PaperOptions paper;
  std::string method = method_name(SlideOptions{});
  std::string density = to_string(PaperOptions{}.density);
  std::string holes = to_string(PaperOptions{}.holes);
  std::string frame_solver = to_string(PaperOptions{}.frame_solver);
  std::string locate = to_string(PaperOptions{}.locate);
  RigOptions rig;          ///< --animation, --fps
  bool has_rig = false;    ///< --animation given: the frames are BIND posed by its skin
  bool keyframes = false;  ///< --keyframes: the default, spelled out
  bool report_no_timings = false;
  bool quiet = false;
  bool verbose = false;
};

/// skinslide's description and version, for CLI::App.
std::string description();

/// Declares every option on `app`, bound into `o`.
void add_options(CLI::App& app, CliOptions& o);

/// After app.parse(): what CLI11 cannot say by itself, conflicts between options and with the
/// BIND's format; sets o.has_rig. \throw CLI::ValidationError naming the option.
void check_options(const CLI::App& app, CliOptions& o);

/// The command line's options as the pipeline's. \throw Error(Usage) on an unknown method name.
RunOptions run_options(const CliOptions& o);

}  // namespace skinslide::cli
