// The command line's options (README "Options"): declared for CLI11, checked, and turned into
// the pipeline's RunOptions. Every option is declared from the library's tables: the command's
// (pipeline/command_options.h), which names the methods' and the run's (core/option.h), with
// their names, kinds, ranges, words, help and groups; every default is the library's own
// (RunOptions, ElasticOptions, PaperOptions): the options are bound straight into those structs,
// and --help shows them.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "pipeline/command_options.h"
#include "skinslide.h"

namespace skinslide::cli {

// The command line's options: the command's table's members (pipeline/command_options.h), bound
// straight into the library's structs, so their defaults are the library's; the word options as
// the words given; and what the declarations leave to check_options.
struct CliOptions : CommandOptions {
  /// The word options as given (--method, --density, ...), by name; run_options() sets them.
  std::map<std::string, std::string> words;
  /// Options one method alone takes, each with that method's name: refused with the other.
  std::vector<std::pair<CLI::Option*, std::string>> method_only;
  /// Options that apply only when a word option has one word (core/option.h Option::needs_option):
  /// the option, the word option's name and that word.
  struct Needs {
    CLI::Option* option;
    std::string word_option;
    std::string word;
  };
  std::vector<Needs> needs;
  /// A flag's conflict (CommandOption::excludes, needs), checked by the flag's value: CLI11 counts
  /// a flag given off (`--quiet=false`, `quiet = false` in a --config file) as given.
  struct FlagRule {
    std::string flag;   ///< "--keyframes"
    std::string other;  ///< "--animation"
    enum Kind { Needs, Excludes } kind;
  };
  std::vector<FlagRule> flag_rules;  ///< in the table's order
  bool has_rig = false;              ///< --animation given: the frames are BIND posed by its skin
};

/// skinslide's description and version, for CLI::App.
std::string description();

/// Declares every option on `app`, bound into `o`.
void add_options(CLI::App& app, CliOptions& o);

/// Parses the command line (and its --config file) into `o`, then checks what CLI11 does not:
/// every key of the config file names an option (cli/config_keys.h), and check_options.
/// \throw CLI::ParseError: CLI11's own, CLI::ConfigError for a config file's unknown key (checked
///        first when the parse fails: a misspelt key may be why), CLI::ValidationError.
void parse(CLI::App& app, CliOptions& o, int argc, char** argv);

/// After app.parse(): what CLI11 cannot say by itself, conflicts between options and with the
/// BIND's format; sets o.has_rig. \throw CLI::ValidationError naming the option.
void check_options(const CLI::App& app, CliOptions& o);

/// The command line's options as the pipeline's.
RunOptions run_options(const CliOptions& o);

}  // namespace skinslide::cli
