#include "config_keys.h"

#include <algorithm>
#include <fstream>
#include <optional>

#include "core/nearest_name.h"

namespace skinslide::cli {
namespace {

// The options a config file may set, by the names CLI11 matches a key against: long names, and a
// positional's name.
std::vector<std::string> option_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* option : app.get_options()) {
    if (!option->get_configurable()) continue;
    for (const std::string& name : option->get_lnames()) names.push_back(name);
    if (option->get_lnames().empty() && option->get_snames().empty())
      names.push_back(option->get_name(true));
  }
  return names;
}

// The option a config key sets, as CLI11 applies a config item (App::_parse_single_config): the
// app has no subcommands, so a key under a section or a dotted prefix names nothing.
const CLI::Option* option_of(const CLI::App& app, const std::vector<std::string>& parents,
                             const std::string& name) {
  if (!parents.empty()) return nullptr;
  if (const CLI::Option* o = app.get_option_no_throw("--" + name)) return o;
  if (name.size() == 1)
    if (const CLI::Option* o = app.get_option_no_throw("-" + name)) return o;
  return app.get_option_no_throw(name);
}

bool names_an_option(const CLI::App& app, const ConfigKey& key) {
  return option_of(app, key.parents, key.name) != nullptr;
}

// Whether CLI11's message is about `option`: "--name: what" (a check), "Could not convert:
// --name = value" (a flag's value), or either side of a conflict, "--a excludes --b" or
// "--a requires --b" (CLI11's words, which check_options uses for the flags' conflicts too).
bool is_about(const std::string& message, const CLI::Option& option) {
  const std::string name = option.get_name();
  const std::string excluded = " excludes " + name;
  return message.rfind(name + ":", 0) == 0 ||
         message.rfind("Could not convert: " + name + " ", 0) == 0 ||
         message.rfind(name + " excludes ", 0) == 0 || message.rfind(name + " requires ", 0) == 0 ||
         (message.size() > excluded.size() &&
          message.compare(message.size() - excluded.size(), excluded.size(), excluded) == 0);
}

// The boolean forms CLI11's documentation gives for a config file (README, "Configuration file"),
// compared in lower case.
bool is_documented_boolean(std::string value) {
  value = CLI::detail::to_lower(value);
  for (const char* form :
       {"true", "false", "on", "off", "yes", "no", "1", "0", "enable", "disable"})
    if (value == form) return true;
  return false;
}

// What is wrong with a flag key's `value`, which is none of the documented boolean forms.
std::string flag_fault(const CLI::Option& option, const std::string& value) {
  return option.get_name() + (value.empty() ? " has an empty value" : " = " + value) +
         ": a flag takes true or false (or on/off, yes/no, 1/0, enable/disable), or the key "
         "alone for true";
}

bool is_flag(const CLI::Option& option) { return option.get_expected_min() == 0; }

std::string full_name(const ConfigKey& key) {
  std::string name;
  for (const std::string& parent : key.parents) name += parent + ".";
  return name + key.name;
}

// The --config file as the checks after a parse read it: its keys with their lines, and CLI11's
// items (none when no file was given, or it cannot be read: CLI11 names that fault).
struct ConfigFile {
  std::string path;
  std::vector<ConfigKey> keys;
  std::vector<CLI::ConfigItem> items;
};

std::optional<ConfigFile> read_config_file(const CLI::App& app) {
  const CLI::Option* config = app.get_config_ptr();
  if (config == nullptr || config->count() == 0) return std::nullopt;
  ConfigFile file{config->results().front(), {}, {}};
  std::ifstream in(file.path);
  if (!in) return std::nullopt;
  file.keys = config_keys(in);
  try {
    file.items = app.get_config_formatter()->from_file(file.path);
  } catch (const CLI::Error&) {
    return std::nullopt;  // the parse named it
  }
  return file;
}

// Refuses the value of the file's top-level key `name`: "<file>:<line>: key '<name>': <fault>".
[[noreturn]] void refuse_key(const ConfigFile& file, const std::string& name,
                             const std::string& fault) {
  long line = 0;
  for (const ConfigKey& key : file.keys)
    if (key.name == name && key.parents.empty()) line = key.line;
  throw CLI::ConfigError(file.path + (line > 0 ? ":" + std::to_string(line) : std::string()) +
                         ": key '" + name + "': " + fault);
}

}  // namespace

std::vector<ConfigKey> config_keys(std::istream& in) {
  namespace detail = CLI::detail;
  std::vector<ConfigKey> keys;
  std::string section = "default";
  long number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    detail::trim(line);
    if (line.size() < 3) continue;
    if (line.front() == '[' && line.back() == ']') {
      section = line.substr(1, line.size() - 2);
      if (section.size() > 1 && section.front() == '[' && section.back() == ']')
        section = section.substr(1, section.size() - 2);  // TOML's [[table]]
      continue;
    }
    if (line.front() == ';' || line.front() == '#') continue;
    ConfigKey key;
    key.line = number;
    const std::size_t equals = line.find('=');
    std::string name = line.substr(0, equals);
    if (equals != std::string::npos) {
      std::string value = detail::trim_copy(line.substr(equals + 1));
      value.erase(std::min(value.find('#'), value.size()));
      detail::trim(value);
      // An array may run over the lines up to its closing bracket: they hold no key.
      if (value.size() > 1 && value.front() == '[')
        for (std::string more; value.back() != ']' && std::getline(in, more); ++number)
          value += detail::trim(more);
    } else {
      name.erase(std::min(name.find('#'), name.size()));
    }
    detail::trim(name);
    if (name.find('.') == std::string::npos) detail::remove_quotes(name);
    key.parents = detail::generate_parents(section, name, '.');
    key.name = name;
    keys.push_back(std::move(key));
  }
  return keys;
}

void check_config_keys(const CLI::App& app) {
  const CLI::Option* config = app.get_config_ptr();
  if (config == nullptr || config->count() == 0) return;
  const std::string path = config->results().front();
  std::ifstream in(path);
  if (!in) return;  // CLI11 names a file it cannot read
  // CLI11 reads the mark as part of the first key: say what it is rather than show it.
  if (in.peek() == 0xEF)
    throw CLI::ConfigError(path +
                           ":1: the file starts with a UTF-8 byte-order mark, which the config "
                           "reader takes as part of the first key; save it without the mark");
  for (const ConfigKey& key : config_keys(in))
    if (!names_an_option(app, key))
      throw CLI::ConfigError(path + ":" + std::to_string(key.line) + ": unknown key '" +
                             full_name(key) + "'; the nearest option is '" +
                             nearest_name(key.name, option_names(app)) + "'");
}

void check_unknown_options(const CLI::App& app) {
  std::vector<std::string> long_names;
  for (const CLI::Option* option : app.get_options())
    for (const std::string& name : option->get_lnames()) long_names.push_back("--" + name);
  for (const std::string& arg : app.remaining()) {
    if (arg.rfind("--", 0) != 0 || arg.size() == 2) continue;  // "--" ends the options
    const std::string name = arg.substr(0, arg.find('='));
    if (app.get_option_no_throw(name) != nullptr) continue;
    throw CLI::ValidationError(name, "unknown option; the nearest option is " +
                                         nearest_name(name, long_names));
  }
}

void check_config_flags(const CLI::App& app) {
  const std::optional<ConfigFile> file = read_config_file(app);
  if (!file) return;
  for (const CLI::ConfigItem& item : file->items) {
    const CLI::Option* option = option_of(app, item.parents, item.name);
    if (option == nullptr || !is_flag(*option) || item.inputs.size() != 1) continue;
    const std::string& value = item.inputs.front();
    if (is_documented_boolean(value)) continue;
    // A flag on the command line wins over the file's (which is then not read), as for values;
    // CLI11 holds the file's value as given, an empty one as "true".
    if (option->results() != std::vector{option->get_flag_value(item.name, value)}) continue;
    refuse_key(*file, item.name, flag_fault(*option, value));
  }
}

void name_config_value(const CLI::App& app, const CLI::ParseError& error) {
  if (error.get_exit_code() == 0) return;
  const std::optional<ConfigFile> file = read_config_file(app);
  if (!file) return;
  const std::string message = error.what();
  for (const CLI::ConfigItem& item : file->items) {
    const CLI::Option* option = option_of(app, item.parents, item.name);
    if (option == nullptr || !is_about(message, *option)) continue;
    // A value on the command line wins over the file's (which is then not read): the file is
    // named only when the option holds the file's value, or none (refused as it was read). Of
    // two options in conflict, the first the file sets is named (`-q` given, `verbose = true`
    // in the file: verbose).
    if (!option->results().empty() && option->results() != item.inputs) continue;
    // A flag's value CLI11 could not convert (`keep-going = maybe`): the flag's own wording.
    if (is_flag(*option) && item.inputs.size() == 1 && !is_documented_boolean(item.inputs.front()))
      refuse_key(*file, item.name, flag_fault(*option, item.inputs.front()));
    refuse_key(*file, item.name, message);
  }
}

}  // namespace skinslide::cli
