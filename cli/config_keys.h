// A --config file's keys, held against the options (README "Controls", config file). CLI11 reads
// a TOML or INI file's values but drops their lines, and passes over a key that names no option:
// a misspelt key would leave its option at the default without a word. Here every key must name
// an option the command line declared (the option tables' and the command line's own).
#pragma once

#include <istream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace skinslide::cli {

/// One key of a config file, where CLI11 reads it.
struct ConfigKey {
  long line = 0;                     ///< 1-based line of the key
  std::vector<std::string> parents;  ///< its [section] (other than "default") and dotted prefix
  std::string name;                  ///< the key itself, quotes removed
};

/// The keys of a TOML or INI config file, read by CLI11's rules (CLI::ConfigBase::from_config):
/// `key = value` or a bare `flag`, `#` and `;` comment lines, [sections], arrays over several
/// lines, lines shorter than 3 characters skipped.
std::vector<ConfigKey> config_keys(std::istream& in);

/// After a parse (or a failed one): with a --config file, each of its keys names an option of
/// `app` as CLI11 finds it (`--key`, `-k`, a positional's name), at the top level.
/// \throw CLI::ConfigError "<file>:<line>: unknown key '<key>'; the nearest option is '<name>'"
///        (nearest by edit distance among the options a config file may set).
void check_config_keys(const CLI::App& app);

/// After a failed parse (cli::parse_error_exit): an argument CLI11 left over that is written as a long option (`--pach`,
/// `--pach=x`) but names none of `app`'s.
/// \throw CLI::ValidationError "--pach: unknown option; the nearest option is --patch" (nearest
///        by edit distance among the long names).
void check_unknown_options(const CLI::App& app);

/// After a parse: with a --config file, each flag (an option without a value: --keep-going, -q)
/// whose value the file gave takes one of the boolean forms CLI11 documents for config files,
/// in any case: true/false, on/off, yes/no, 1/0, enable/disable, or the key alone (= true).
/// CLI11 reads any other integer as on (`keep-going = 5`; a negative one as off).
/// \throw CLI::ConfigError "<file>:<line>: key '<key>': --<name> = <value>: a flag takes ...".
void check_config_flags(const CLI::App& app);

/// After a parse or a check of the options failed with `error`: when the value refused is a
/// --config file's (the option holds that file's value, or was refused as the file was read),
/// throws the same message naming the file, the key's line and the key; of two options in
/// conflict ("--quiet excludes --verbose"), the first key of the file that holds its value.
/// \throw CLI::ConfigError "<file>:<line>: key '<key>': <error's message>"; returns otherwise.
void name_config_value(const CLI::App& app, const CLI::ParseError& error);

}  // namespace skinslide::cli
