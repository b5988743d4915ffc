#include "command_line.h"

#include <cmath>
#include <map>
#include <type_traits>
#include <variant>

#include "config_keys.h"
#include "core/file_extension.h"
#include "core/version.h"
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

// Inputs and glTF.
void add_inputs(CLI::App& app, CliOptions& o) {
  const char* in = "Inputs";
  app.add_option("bind", o.run.bind, "Bind mesh (.obj, .gltf, .glb)")
      ->required()
      ->type_name("BIND")
      ->group(in);
  auto* frames =
      app.add_option("frames", o.run.frames,
                     "Deformed frames: the bind mesh with moved vertices, or one point cache of "
                     "them (.pc2, .mdd)")
          ->type_name("FRAME...")
          ->group(in);
  app.add_option("--patch", o.run.patches,
                 "Patch file (repeatable; each file's patches are separate); required, unless "
                 "--no-slide")
      ->allow_extra_args(false)
      ->type_name("FILE")
      ->group(in);
  app.add_flag("--bind-is-frame", o.run.bind_is_frame,
               "Take a BIND named as a member of the FRAME sequence (frames/arm.0001.obj with "
               "frames/arm.0002.obj ...), refused otherwise as a forgotten bind")
      ->group(in);
  const char* gl = "glTF";
  app.add_option("--mesh", o.run.mesh, "Mesh of a .gltf/.glb holding several (name, else index)")
      ->type_name("NAME|INDEX")
      ->group(gl);
  app.add_option("--allow-uri-outside", o.run.allow_uri_outside,
                 "Also read glTF buffers from this folder's tree (repeatable); else a glTF reads "
                 "only data: URIs and files inside its own folder")
      ->check(CLI::Validator(CLI::ExistingDirectory).description(""))  // help: "DIR", not "DIR:DIR"
      ->allow_extra_args(false)
      ->type_name("DIR")
      ->group(gl);
  app.add_option("--animation", o.rig.animation,
                 "BIND is an animated glTF character (skin and/or morph targets): "
                 "pose it at each sampled time of this clip (name, else index) and "
                 "slide those frames")
      ->type_name("NAME|INDEX")
      ->excludes(frames)
      ->group(gl);
  app.add_option("--fps", o.rig.fps,
                 "Sample the clip every 1/N s from its first key to its last; with "
                 "FRAME files and --format mdd, their rate (frame n at n/N s)")
      ->check(a_number())
      ->check(CLI::Range(0.001, 100000.0))
      ->type_name("N")
      ->group(gl);
  // Needs --animation and excludes --fps when on: check_flag_conflicts.
  app.add_flag("--keyframes", o.keyframes,
               "Sample the clip at its key times (the default; with --animation, not with --fps)")
      ->group(gl);
  app.add_option("--format", o.run.format,
                 "Format of the slid frames of --animation (default glb; frames "
                 "<character>.<frame>.<format> from 0000) or of a point cache FRAME (default its "
                 "own): obj or glb, a file a frame; pc2 or mdd, one cache. FRAME files: pc2 or "
                 "mdd writes them as one cache (default: each in its own format)")
      ->check(CLI::IsMember({"obj", "glb", "pc2", "mdd"}))
      ->group(gl);
}

void add_outputs(CLI::App& app, CliOptions& o) {
  const char* out = "Output";
  app.add_option("-o,--output", o.run.output,
                 "Folder for the slid frames (same file names); a run writing one cache may "
                 "name it: shot.pc2")
      ->capture_default_str()
      ->type_name("DIR")
      ->group(out);
  app.add_option("--dump", o.run.dump_dir,
                 "Folder for EXR images of each patch's 2D layout (elastic: its chart; paper: its "
                 "nets): ID lookup image and geometry image (P, coverage, slide field), for the "
                 "bind and every frame (off by default)")
      ->type_name("DIR")
      ->group(out);
  app.add_option("--preview", o.run.preview_dir,
                 "Folder for a PNG per frame and patch: the bind's and the frame's 2D layouts "
                 "drawn over each other, slides marked (off by default)")
      ->type_name("DIR")
      ->group(out);
  app.add_option("--preview-size", o.run.preview_size, "Side of the preview PNGs, pixels")
      ->capture_default_str()
      ->check(CLI::Range(16, 8192))
      ->group(out);
}

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

// --help's group of the solvers' internals (core/option.h Option::research; each documented in
// lib/elastic/README.md and lib/paper/README.md).
constexpr const char* kResearchGroup = "Research";

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

// The names of a table's options that are choices (not research), as "--a, --b".
template <class Options>
std::string choice_names() {
  std::string out;
  for (const Option<Options>& option : option_table<Options>())
    if (!option.research) out += (out.empty() ? "--" : ", --") + option.name;
  return out;
}

// The Method group in README's order: --method, the elastic options (--window last), the paper's.
void add_method(CLI::App& app, CliOptions& o) {
  const char* method = "Method";
  // The help says where each method's options are in this group (its table's text cannot: it
  // does not know the help's order).
  add_table_option(app, method_option(), o.run, o, method)
      ->description(
          "elastic: the free vertices slide in a fixed chart of each patch towards the bind's "
          "edge lengths (its options: " +
          choice_names<ElasticOptions>() + ", --" + window_option().name + ", --" +
          window_ends_option().name +
          "); paper: Yang & Zhang's bar nets, one linear solve a frame (its options: in "
          "Research)");
  add_method_options(app, o.elastic, o, method, false);
  // A run's option, not a frame's (pipeline/run_options.h window_option).
  CLI::Option* window = add_table_option(app, window_option(), o.run, o, method)->type_name("N");
  o.method_only.push_back({window, method_name(ElasticOptions{})});
  CLI::Option* ends = add_table_option(app, window_ends_option(), o.run, o, method);
  o.method_only.push_back({ends, method_name(ElasticOptions{})});
  add_method_options(app, o.paper, o, method, false);
}

// The solvers' internals, last in --help: no choice a user makes.
void add_research(CLI::App& app, CliOptions& o) {
  add_method_options(app, o.elastic, o, kResearchGroup, true);
  add_method_options(app, o.paper, o, kResearchGroup, true);
}

void add_run(CLI::App& app, CliOptions& o) {
  const char* run = "Run";
  app.add_option("-j,--threads", o.run.threads,
                 "Frames processed at once; 0 = every core this task may use (its CPU affinity)")
      ->capture_default_str()
      ->check(CLI::Range(0u, 1024u))
      ->group(run);
  app.add_option("--frames", o.run.frame_ranges,
                 "Only the frames whose file names carry these numbers (name.0042.obj -> 42): "
                 "1-100, 1-100:5 (every 5th), 3,7,12-20; ranges past the frames given are clamped")
      ->type_name("RANGES")
      ->group(run);
  app.add_flag("--keep-going", o.run.keep_going,
               "Write every good frame and name every bad one, instead of stopping at the first "
               "(exit code: the first bad frame's)")
      ->group(run);
  app.add_flag("--require-converged", o.run.require_converged,
               "Fail a frame (exit 5, naming frame and patch) when a patch's elastic slide did "
               "not converge, instead of writing it and logging 'not converged'")
      ->group(run);
  app.add_flag("--no-slide", o.run.no_slide,
               "Read, check and write every frame unchanged, without sliding (no --patch needed): "
               "the I/O floor of a run, or a sequence converted into a cache (--format pc2)")
      ->group(run);
  app.add_flag("-q,--quiet", o.quiet, "Errors only (not with --verbose)")->group(run);
  app.add_flag("-v,--verbose", o.verbose, "Per-patch detail (not with --quiet)")->group(run);
  app.set_config("--config", "",
                 "Read options from a TOML or INI file (`density = \"paper\"`); "
                 "the command line overrides it")
      ->type_name("FILE")
      ->check(CLI::ExistingFile)
      ->group(run);
  // Declared again after the others, so that --help lists them here, in Run, as README does.
  app.set_help_flag();
  app.set_help_flag("-h,--help", "Print this help and exit")->group(run);
  app.set_version_flag("--version", std::string("skinslide ") + version(),
                       "Print the version and exit")
      ->group(run);
}

// Controls and the report.
void add_controls(CLI::App& app, CliOptions& o) {
  const char* controls = "Controls";
  auto* weights =
      app.add_option("--weights", o.run.weights,
                     "Slide weights in [0,1]: one a line in vertex order, or 'index weight' pairs "
                     "(unlisted = 0); a vertex of weight w slides w of its way (elastic: in the "
                     "chart, staying on the surface; paper: lerp(frame, slid, w) in 3D)")
          ->type_name("FILE")
          ->group(controls);
  app.add_option(
         "--weights-from-obj-color", o.run.weights_from_obj_color,
         "Slide weights from the bind OBJ's vertex colours (v x y z r g b, or r g b a: alpha "
         "ignored), this channel")
      ->check(CLI::IsMember({"r", "g", "b"}))
      ->excludes(weights)
      ->group(controls);
  app.add_option("--weights-from-gltf-attribute", o.run.weights_from_gltf_attribute,
                 "Slide weights from this vertex attribute of the bind glTF's mesh (e.g. "
                 "_SLIDE_WEIGHT): SCALAR float, or normalized unsigned byte/short, on every "
                 "triangle primitive; a welded vertex takes its first raw copy's weight")
      ->type_name("NAME")
      ->excludes(weights)
      ->excludes("--weights-from-obj-color")
      ->group(controls);
  add_table_option(app, strength_option(), o.run, o, controls);
  app.add_option("--pin", o.run.pin,
                 "Vertex ids that do not slide (12, 12-40, pBody.vtx[12:40]); the skin around "
                 "them does")
      ->type_name("FILE")
      ->group(controls);
  auto* corners =
      app.add_option("--corners", o.run.corners,
                     "Paper: four vertex ids on a patch's boundary loop, in walking order, for the "
                     "square's corners (0,0) (1,0) (1,1) (0,1); that loop becomes the outer loop "
                     "(repeatable: one per patch)")
          ->type_name("A,B,C,D")
          ->allow_extra_args(false)
          ->group(controls);
  o.method_only.push_back({corners, method_name(PaperOptions{})});  // the elastic chart is a disk
  app.add_option("--outer-loop-vertex", o.run.outer_loop_vertices,
                 "A vertex id on the boundary loop to put on the outer border (the elastic "
                 "chart's circle, the paper's square; repeatable: one per patch)")
      ->type_name("V")
      ->allow_extra_args(false)
      ->check(CLI::Range(0, 2147483647))
      ->group(controls);
  app.add_option("--report", o.run.report,
                 "Write a JSON report: per frame and patch the method's figures "
                 "(elastic: energy, steps; paper: CG, location), slide and "
                 "edge-spread figures, totals and timings")
      ->type_name("FILE.json")
      ->group(controls);
  // Needs --report when on: check_flag_conflicts.
  app.add_flag("--report-no-timings", o.report_no_timings,
               "Leave the timings out of the --report (it then depends on the inputs only)")
      ->group(controls);
}

// Whether option `name` was given and, a flag, given on: CLI11's excludes() and needs() count a
// flag given off (`--quiet=false`, `quiet = false` in a --config file) as given.
bool is_on(const CLI::App& app, const std::string& name) {
  const CLI::Option* option = app.get_option(name);
  return option->count() > 0 && (option->get_expected_min() != 0 || option->as<bool>());
}

// The flags' conflicts, by value, in CLI11's words.
void check_flag_conflicts(const CLI::App& app) {
  if (is_on(app, "--keyframes") && !is_on(app, "--animation"))
    throw CLI::RequiresError("--keyframes", "--animation");
  if (is_on(app, "--keyframes") && is_on(app, "--fps"))
    throw CLI::ExcludesError("--keyframes", "--fps");
  if (is_on(app, "--quiet") && is_on(app, "--verbose"))
    throw CLI::ExcludesError("--quiet", "--verbose");
  if (is_on(app, "--report-no-timings") && !is_on(app, "--report"))
    throw CLI::RequiresError("--report-no-timings", "--report");
}

}  // namespace

std::string description() { return "skinslide " + std::string(version()) + kDescription; }

void add_options(CLI::App& app, CliOptions& o) {
  add_inputs(app, o);
  add_outputs(app, o);
  add_method(app, o);
  add_run(app, o);
  add_controls(app, o);
  add_research(app, o);
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
  check_flag_conflicts(app);
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
  const RunOptions& r = o.run;
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
  if (!cache_frame && app.count("--format") == 0) o.run.format = cache_format_named_by(r.output);
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
  RunOptions r = with_words(o.run, o.words);  // the method named, with its defaults
  r.window_ends = window_ends_named(o.words.at(window_ends_option().name));
  if (o.has_rig)
    r.rig = o.rig;
  else if (r.format == "mdd")
    r.fps = o.rig.fps;
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
