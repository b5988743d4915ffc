#include "command_line.h"

#include <cmath>
#include <map>
#include <type_traits>
#include <variant>

#include "config_keys.h"
#include "core/check.h"
#include "core/file_extension.h"
#include "core/version.h"
#include "pipeline/command_options.h"
#include "pipeline/frame_plans.h"

namespace skinslide::cli {
namespace {

// CLI11's Range asks only "below low or above high?", which NaN is not: a number option must be a
// number. (No description: --help shows the range alone.)
CLI::Validator a_number() {
  return CLI::Validator(
      [](std::string& text) {
        double x = 0;
        return CLI::detail::lexical_cast(text, x) && std::isnan(x)
                   ? "Value " + text + " is not a number"
                   : std::string();
      },
      "");
}

// Paragraphs, one a line; the help wraps them (help_format.h). Lines starting with spaces are
// commands, kept as they are.
const char* const kDescription =
    ": skin sliding for deformed character meshes.\n"
    "Moves each patch's free vertices along the frame's surface so that the skin's bind edge "
    "lengths come back: by default (--method elastic) they relax in a fixed chart of the patch "
    "towards the bind's shape with fold-free, energy-decreasing steps; --method paper flattens "
    "bind and frame with force-density bar nets (Yang & Zhang 2010). The patch border and holes "
    "never move.\n"
    "Patch files list 0-based face ids of the bind (OBJ `f` lines in file order): `12`, `12-40`, "
    "`pBody.f[12:40]`; whitespace or commas between them, `#` comments. For .gltf/.glb the faces "
    "are the triangles of the mesh's triangle primitives, in primitive order (vertices welded by "
    "position for connectivity only).\n"
    "A rigged glTF character can be its own frame source:\n"
    "  skinslide --patch P.txt --animation NAME|INDEX [--fps N | --keyframes] character.glb\n"
    "A point cache (.pc2, .mdd) of the bind's vertices is a whole shot: one FRAME, slid sample by "
    "sample into a cache of the same name (a --frames chunk: <shot>.<first>-<last>.pc2); chunks "
    "join with\n"
    "  skinslide join [-o DIR] CHUNK...\n"
    "Two slid outputs (folders of frames, or caches) compare as meshes, for CI, with\n"
    "  skinslide compare [--tolerance T] [--common] A B";

// A table's option (core/option.h) declared for CLI11 in `group`: a number bound to its member of
// `options` (CLI11 shows the member's value as the default) and checked against its range; a word
// bound to o.words[name], checked against its words and set into `options` by run_options().
template <class Options>
CLI::Option* add_table_option(CLI::App& app, const Option<Options>& option, Options& options,
                              CliOptions& o, const char* group) {
  const std::string name = "--" + option.name;
  CLI::Option* added = std::visit(
      [&](const auto& value) {
        if constexpr (requires { value.member; }) {
          return app.add_option(name, options.*value.member, option.help)
              ->capture_default_str()
              ->check(a_number())
              ->check(CLI::Range(value.low, value.high));
        } else {
          std::string& word = o.words[option.name] = value.get(options);
          return app.add_option(name, word, option.help)
              ->capture_default_str()
              ->check(CLI::IsMember(value.words));
        }
      },
      option.value);
  return added->group(group);
}

// A method's options of one kind (its choices, or its internals: Option::research), from its
// table: each refused with the other method (check_options), but an option the run also reads
// whatever the method (--lookup-size, for --dump), and one that needs another's word without it.
template <class Options>
void add_method_options(CLI::App& app, Options& options, CliOptions& o, const char* group,
                        bool research) {
  const std::string method = method_name(options);
  for (const Option<Options>& option : option_table<Options>()) {
    if (option.research != research) continue;
    CLI::Option* added = add_table_option(app, option, options, o, group);
    if (!option.run_wide) o.method_only.push_back({added, method});
    if (option.needs_option) o.needs.push_back({added, option.needs_option, option.needs_word});
  }
}

// How CLI11 names an entry of the command's table: "bind", "--patch", "-o,--output".
std::string cli_names(const CommandOption& entry) {
  if (entry.positional) return entry.name;
  return (entry.short_name ? "-" + std::string(entry.short_name) + "," : std::string()) + "--" +
         entry.name;
}

// The entry's value declared for CLI11, bound into `o`: nullptr for a method's options, which
// add_method_options declares each with its own group.
CLI::Option* add_value(CLI::App& app, const CommandOption& entry, CliOptions& o) {
  const std::string names = cli_names(entry);
  return std::visit(
      [&](const auto& value) -> CLI::Option* {
        using Value = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<Value, FlagOption>) {
          return app.add_flag(names, o.*value.member, entry.help);
        } else if constexpr (std::is_same_v<Value, TextOption>) {
          CLI::Option* added = app.add_option(names, o.*value.member, entry.help);
          return value.words.empty() ? added : added->check(CLI::IsMember(value.words));
        } else if constexpr (std::is_same_v<Value, TextListOption>) {
          CLI::Option* added = app.add_option(names, o.*value.member, entry.help);
          return entry.positional ? added : added->allow_extra_args(false);
        } else if constexpr (std::is_same_v<Value, IndexListOption>) {
          return app.add_option(names, o.*value.member, entry.help)
              ->allow_extra_args(false)
              ->check(CLI::Range(value.low, value.high));
        } else if constexpr (std::is_same_v<Value, RunTableOption>) {
          CLI::Option* added =
              add_table_option(app, value.option(), static_cast<RunOptions&>(o), o, entry.group);
          return entry.help.empty() ? added : added->description(entry.help);
        } else if constexpr (std::is_same_v<Value, MethodTableOptions<ElasticOptions>>) {
          add_method_options(app, o.elastic, o, entry.group, value.research);
          return nullptr;
        } else if constexpr (std::is_same_v<Value, MethodTableOptions<PaperOptions>>) {
          add_method_options(app, o.paper, o, entry.group, value.research);
          return nullptr;
        } else if constexpr (std::is_same_v<Value, ConfigFileOption>) {
          return app.set_config(names, "", entry.help);
        } else if constexpr (std::is_same_v<Value, HelpFlag>) {
          // Declared again, after the others, so that --help lists it in its group.
          app.set_help_flag();
          return app.set_help_flag(names, entry.help);
        } else if constexpr (std::is_same_v<Value, VersionFlag>) {
          return app.set_version_flag(names, std::string("skinslide ") + version(), entry.help);
        } else {  // a number
          CLI::Option* added = app.add_option(names, o.*value.member, entry.help);
          if (entry.refuse_nan) added->check(a_number());
          return added->check(CLI::Range(value.low, value.high));
        }
      },
      entry.value);
}

// The option CLI11 knows by `name` ("--weights", "frames"), declared before.
CLI::Option* declared(CLI::App& app, const std::string& name) {
  CLI::Option* option = app.get_option_no_throw(name);
  SKINSLIDE_CHECK(option != nullptr, "the command's table names " + name + " before it");
  return option;
}

// One entry of the command's table declared for CLI11, with its spelling, its checks and its
// conflicts (a flag's kept in `o.flag_rules`, checked by value after the parse).
void add_command_option(CLI::App& app, const CommandOption& entry, CliOptions& o) {
  CLI::Option* added = add_value(app, entry, o);
  if (added == nullptr) return;
  if (entry.show_default) added->capture_default_str();
  if (entry.check == PathCheck::ExistingFile) added->check(CLI::ExistingFile);
  // help: "DIR", not "DIR:DIR"
  if (entry.check == PathCheck::ExistingDirectory)
    added->check(CLI::Validator(CLI::ExistingDirectory).description(""));
  if (entry.type_name) added->type_name(entry.type_name);
  if (entry.required) added->required();
  added->group(entry.group);
  if (entry.method) o.method_only.push_back({added, entry.method});
  const bool flag = std::holds_alternative<FlagOption>(entry.value);
  for (const std::string& other : entry.needs)
    if (flag)
      o.flag_rules.push_back({added->get_name(), other, CliOptions::FlagRule::Needs});
    else
      added->needs(declared(app, other));
  for (const std::string& other : entry.excludes)
    if (flag)
      o.flag_rules.push_back({added->get_name(), other, CliOptions::FlagRule::Excludes});
    else
      added->excludes(declared(app, other));
}

// Whether option `name` was given and, a flag, given on: CLI11's excludes() and needs() count a
// flag given off (`--quiet=false`, `quiet = false` in a --config file) as given.
bool is_on(const CLI::App& app, const std::string& name) {
  const CLI::Option* option = app.get_option(name);
  return option->count() > 0 && (option->get_expected_min() != 0 || option->as<bool>());
}

// The flags' conflicts, by value, in CLI11's words, in the table's order.
void check_flag_conflicts(const CLI::App& app, const CliOptions& o) {
  for (const CliOptions::FlagRule& rule : o.flag_rules) {
    if (!is_on(app, rule.flag)) continue;
    if (rule.kind == CliOptions::FlagRule::Needs && !is_on(app, rule.other))
      throw CLI::RequiresError(rule.flag, rule.other);
    if (rule.kind == CliOptions::FlagRule::Excludes && is_on(app, rule.other))
      throw CLI::ExcludesError(rule.flag, rule.other);
  }
}

}  // namespace

std::string description() { return "skinslide " + std::string(version()) + kDescription; }

void add_options(CLI::App& app, CliOptions& o) {
  for (const CommandOption& entry : command_option_table()) add_command_option(app, entry, o);
}

void parse(CLI::App& app, CliOptions& o, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // A misspelt key leaves its option unset: a required option then seems missing.
    if (e.get_exit_code() != 0) check_config_keys(app);
    name_config_value(app, e);
    throw;
  }
  check_config_keys(app);
  check_config_flags(app);
  try {
    check_options(app, o);
  } catch (const CLI::ParseError& e) {
    name_config_value(app, e);
    throw;
  }
}

void check_options(const CLI::App& app, CliOptions& o) {
  o.has_rig = app.count("--animation") > 0;
  check_flag_conflicts(app, o);
  // Options of one method only are refused with the other, naming both.
  const std::string& method = o.words.at(method_option().name);
  for (const auto& [option, only] : o.method_only)
    if (only != method && option->count() > 0)
      throw CLI::ValidationError(
          option->get_name(), "applies to --method " + only + " only, not to --method " + method);
  for (const CliOptions::Needs& needs : o.needs)
    if (needs.option->count() > 0 && o.words.at(needs.word_option) != needs.word)
      throw CLI::ValidationError(needs.option->get_name(),
                                 "applies to --" + needs.word_option + " " + needs.word +
                                     " only, not to --" + needs.word_option + " " +
                                     o.words.at(needs.word_option));
  const CommandOptions& r = o;
  if (app.count("--" + window_ends_option().name) > 0 && r.window == 0)
    throw CLI::ValidationError("--" + window_ends_option().name,
                               "says where --window's frames end: give --window N too");
  if (r.patches.empty() && !r.no_slide) throw CLI::RequiredError("--patch");
  if (r.no_slide &&
      (o.has_rig || !r.report.empty() || !r.dump_dir.empty() || !r.preview_dir.empty()))
    throw CLI::ValidationError(
        "--no-slide",
        "copies frame files only: not with --animation, --report, --dump or --preview");
  if (!o.has_rig && r.frames.empty())
    throw CLI::ValidationError("FRAME...",
                               "give at least one FRAME, or --animation with a rigged glTF BIND");
  const bool cache_frame = r.frames.size() == 1 && cache_format(r.frames.front());
  const bool frame_files = !o.has_rig && !cache_frame;
  // `-o shot.pc2` with no --format names the cache to write (pipeline/frame_plans.h).
  if (!cache_frame && app.count("--format") == 0) o.format = cache_format_named_by(r.output);
  if (app.count("--format") > 0 && frame_files && (r.format == "obj" || r.format == "glb"))
    throw CLI::ValidationError("--format",
                               "obj or glb applies to --animation or a point cache FRAME (.pc2, "
                               ".mdd); FRAME files are written in their own formats, or as one "
                               "cache: --format pc2 or mdd");
  if (app.count("--fps") > 0 && !o.has_rig && !(frame_files && r.format == "mdd"))
    throw CLI::ValidationError("--fps",
                               "applies to --animation, or to FRAME files written as one MDD "
                               "cache (--format mdd)");
  const std::string ext = lower_extension(r.bind);
  const bool gltf_bind = ext == ".gltf" || ext == ".glb";
  if (o.has_rig && !gltf_bind)
    throw CLI::ValidationError("--animation", "needs a .gltf or .glb BIND, not " + r.bind);
  if (cache_frame && r.format == "glb" && !gltf_bind)
    throw CLI::ValidationError("--format", "glb from a point cache needs a .gltf or .glb BIND");
  if (app.count("--weights-from-gltf-attribute") > 0 && r.weights_from_gltf_attribute.empty())
    throw CLI::ValidationError("--weights-from-gltf-attribute", "needs an attribute name");
  if (!r.weights_from_gltf_attribute.empty() && !gltf_bind)
    throw CLI::ValidationError("--weights-from-gltf-attribute",
                               "needs a .gltf or .glb BIND, not " + r.bind);
}

// `options` with its word options set from the words given.
template <class Options>
Options with_words(Options options, const std::map<std::string, std::string>& words) {
  for (const Option<Options>& option : option_table<Options>())
    if (const auto* word = std::get_if<WordOption<Options>>(&option.value))
      word->set(options, words.at(option.name));
  return options;
}

RunOptions run_options(const CliOptions& o) {
  // The method named, with its defaults.
  RunOptions r = with_words(static_cast<const RunOptions&>(o), o.words);
  r.window_ends = window_ends_named(o.words.at(window_ends_option().name));
  // --fps is the clip's rate with --animation, the cache's with FRAME files written as MDD.
  if (o.has_rig) r.rig = RigOptions{o.animation, o.fps};
  if (o.has_rig || r.format != "mdd") r.fps = 0;
  r.report_timings = !o.report_no_timings;
  r.lookup_size = o.paper.lookup_size;
  std::visit(
      [&](auto& slide) {
        using Options = std::decay_t<decltype(slide)>;
        if constexpr (std::is_same_v<Options, ElasticOptions>)
          slide = with_words(o.elastic, o.words);
        else
          slide = with_words(o.paper, o.words);
      },
      r.slide);
  return r;
}

}  // namespace skinslide::cli
