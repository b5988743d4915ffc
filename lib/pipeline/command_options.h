// The command's table (core/option.h): every option of `skinslide` declared once, in --help's
// order, with its group (--help's heading), its kind (a number, a word, a flag, a path or a name,
// a repeatable one, a list of vertex ids), its range or words, its help and how the command line
// spells it (short name, argument name, default shown, the options it excludes or needs). The
// methods' options and the run's shared ones are not copied here: an entry names their table
// (elastic/elastic_options.h, paper/paper_options.h, pipeline/run_options.h), which the Python
// module and the Blender add-on read too. cli/command_line.cpp walks this table and declares each
// option for CLI11; adding an option to the command is adding one entry here (or to a method's
// table) and the member it sets.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "core/option.h"
#include "core/types.h"
#include "pipeline/run_options.h"

namespace skinslide {

/// What the command line sets, bound straight into the library's structs so that every default
/// is the library's: the run's options (RunOptions, whose members a table entry names as its
/// own), each method's, and the command's own switches. run_options() in cli/ makes the
/// pipeline's RunOptions of it.
struct CommandOptions : RunOptions {
  ElasticOptions elastic;  ///< the elastic method's options (its table)
  PaperOptions paper;      ///< the paper method's options (its table)
  std::string animation;   ///< --animation: clip name or index; given = BIND is a rigged glTF
  bool keyframes = false;  ///< --keyframes: the default sampling, spelled out
  bool report_no_timings = false;  ///< --report-no-timings
  bool quiet = false;              ///< -q: errors only
  bool verbose = false;            ///< -v: per-patch detail
};

/// A flag: an option without a value, on when given.
struct FlagOption {
  bool CommandOptions::*member;
};

/// A value taken as written (a path, a name, an index): `words`, when any, are all it may be.
struct TextOption {
  std::string CommandOptions::*member;
  std::vector<std::string> words = {};
};

/// A repeatable value (--patch FILE ...), each given in order.
struct TextListOption {
  std::vector<std::string> CommandOptions::*member;
};

/// A repeatable vertex id (--outer-loop-vertex), each in [low, high].
struct IndexListOption {
  std::vector<Index> CommandOptions::*member;
  Index low;
  Index high;
};

/// One option of a run's table (run_options.h: --method, --strength, --window, --window-ends).
struct RunTableOption {
  const Option<RunOptions>& (*option)();
};

/// The options of a method's table that are its choices (`research` false) or its internals
/// (core/option.h Option::research), in the table's order.
template <class Options>
struct MethodTableOptions {
  bool research;
};

/// --config FILE: a TOML or INI file of options (cli/config_keys.h).
struct ConfigFileOption {};
/// --help, --version: print and exit.
struct HelpFlag {};
struct VersionFlag {};

using CommandValue =
    std::variant<NumberOption<CommandOptions, int>, NumberOption<CommandOptions, unsigned>,
                 NumberOption<CommandOptions, double>, FlagOption, TextOption, TextListOption,
                 IndexListOption, RunTableOption, MethodTableOptions<ElasticOptions>,
                 MethodTableOptions<PaperOptions>, ConfigFileOption, HelpFlag, VersionFlag>;

/// A path option's check, made before the run.
enum class PathCheck { None, ExistingFile, ExistingDirectory };

/// One entry of the command's table. For a table's options (RunTableOption, MethodTableOptions)
/// only `group`, `help` (set: replaces the table's), `type_name` and `method` apply.
struct CommandOption {
  /// The long name ("patch": --patch, and a --config file's key); a positional's own ("bind").
  std::string name;
  std::string help;
  const char* group;  ///< --help's heading
  CommandValue value;
  const char* short_name = nullptr;  ///< "o": -o too
  const char* type_name = nullptr;   ///< the argument's name in --help ("FILE"); null: its kind's
  bool positional = false;
  bool required = false;
  bool show_default = false;  ///< --help gives the default
  /// A number given as "nan" is refused as no number (a range alone lets NaN through).
  bool refuse_nan = false;
  PathCheck check = PathCheck::None;
  /// Options this one is not given with, and options it needs, as the command line names them
  /// ("--weights"; a positional by its own name, "frames"). A flag's are checked by its value
  /// (`--quiet=false` is not given) after the parse; the others' excludes by CLI11.
  std::vector<std::string> excludes = {};
  std::vector<std::string> needs = {};
  /// Set: the method ("elastic", "paper") this option applies to; refused with the other.
  const char* method = nullptr;
};

/// Every option of `skinslide`, in --help's order within each group and the groups in the order
/// --help shows them (the first entry of each).
const std::vector<CommandOption>& command_option_table();

/// --help's group of the solvers' internals (core/option.h Option::research).
constexpr const char* kResearchGroup = "Research";

}  // namespace skinslide
