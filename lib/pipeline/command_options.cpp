#include "pipeline/command_options.h"

namespace skinslide {
namespace {

using C = CommandOptions;

constexpr const char* kInputs = "Inputs";
constexpr const char* kGltf = "glTF";
constexpr const char* kOutput = "Output";
constexpr const char* kMethod = "Method";
constexpr const char* kRun = "Run";
constexpr const char* kControls = "Controls";

// The names of a table's options that are choices (not research), as "--a, --b".
template <class Options>
std::string choice_names() {
  std::string out;
  for (const Option<Options>& option : option_table<Options>())
    if (!option.research) out += (out.empty() ? "--" : ", --") + option.name;
  return out;
}

// --method's help in the command: where each method's options are in --help (the run's table
// cannot say: it does not know the help's order).
std::string method_help() {
  return "elastic: the free vertices slide in a fixed chart of each patch towards the bind's "
         "edge lengths (its options: " +
         choice_names<ElasticOptions>() + ", --" + window_option().name + ", --" +
         window_ends_option().name +
         "); paper: Yang & Zhang's bar nets, one linear solve a frame (its options: in "
         "Research)";
}

std::vector<CommandOption> inputs_and_gltf() {
  return {
      {.name = "bind",
       .help = "Bind mesh (.obj, .gltf, .glb)",
       .group = kInputs,
       .value = TextOption{&C::bind},
       .type_name = "BIND",
       .positional = true,
       .required = true},
      {.name = "frames",
       .help = "Deformed frames: the bind mesh with moved vertices, or one point cache of them "
               "(.pc2, .mdd)",
       .group = kInputs,
       .value = TextListOption{&C::frames},
       .type_name = "FRAME...",
       .positional = true},
      {.name = "patch",
       .help = "Patch file (repeatable; each file's patches are separate); required, unless "
               "--no-slide",
       .group = kInputs,
       .value = TextListOption{&C::patches},
       .type_name = "FILE"},
      {.name = "bind-is-frame",
       .help = "Take a BIND named as a member of the FRAME sequence (frames/arm.0001.obj with "
               "frames/arm.0002.obj ...), refused otherwise as a forgotten bind",
       .group = kInputs,
       .value = FlagOption{&C::bind_is_frame}},
      {.name = "mesh",
       .help = "Mesh of a .gltf/.glb holding several (name, else index)",
       .group = kGltf,
       .value = TextOption{&C::mesh},
       .type_name = "NAME|INDEX"},
      {.name = "allow-uri-outside",
       .help = "Also read glTF buffers from this folder's tree (repeatable); else a glTF reads "
               "only data: URIs and files inside its own folder",
       .group = kGltf,
       .value = TextListOption{&C::allow_uri_outside},
       .type_name = "DIR",
       .check = PathCheck::ExistingDirectory},
      {.name = "animation",
       .help = "BIND is an animated glTF character (skin and/or morph targets): pose it at each "
               "sampled time of this clip (name, else index) and slide those frames",
       .group = kGltf,
       .value = TextOption{&C::animation},
       .type_name = "NAME|INDEX",
       .excludes = {"frames"}},
      {.name = "fps",
       .help = "Sample the clip every 1/N s from its first key to its last; with FRAME files and "
               "--format mdd, their rate (frame n at n/N s)",
       .group = kGltf,
       .value = NumberOption<C, double>{&C::fps, 0.001, 100000.0},
       .type_name = "N",
       .refuse_nan = true},
      {.name = "keyframes",
       .help = "Sample the clip at its key times (the default; with --animation, not with --fps)",
       .group = kGltf,
       .value = FlagOption{&C::keyframes},
       .excludes = {"--fps"},
       .needs = {"--animation"}},
      {.name = "format",
       .help = "Format of the slid frames of --animation (default glb; frames "
               "<character>.<frame>.<format> from 0000) or of a point cache FRAME (default its "
               "own): obj or glb, a file a frame; pc2 or mdd, one cache. FRAME files: pc2 or mdd "
               "writes them as one cache (default: each in its own format)",
       .group = kGltf,
       .value = TextOption{&C::format, {"obj", "glb", "pc2", "mdd"}}},
  };
}

std::vector<CommandOption> outputs_and_method() {
  return {
      {.name = "output",
       .help = "Folder for the slid frames (same file names); a run writing one cache may name "
               "it: shot.pc2",
       .group = kOutput,
       .value = TextOption{&C::output},
       .short_name = "o",
       .type_name = "DIR",
       .show_default = true},
      {.name = "dump",
       .help = "Folder for EXR images of each patch's 2D layout (elastic: its chart; paper: its "
               "nets): ID lookup image and geometry image (P, coverage, slide field), for the "
               "bind and every frame (off by default)",
       .group = kOutput,
       .value = TextOption{&C::dump_dir},
       .type_name = "DIR"},
      {.name = "preview",
       .help = "Folder for a PNG per frame and patch: the bind's and the frame's 2D layouts "
               "drawn over each other, slides marked (off by default)",
       .group = kOutput,
       .value = TextOption{&C::preview_dir},
       .type_name = "DIR"},
      {.name = "preview-size",
       .help = "Side of the preview PNGs, pixels",
       .group = kOutput,
       .value = NumberOption<C, int>{&C::preview_size, 16, 8192},
       .show_default = true},
      {.name = "method",
       .help = method_help(),
       .group = kMethod,
       .value = RunTableOption{&method_option}},
      {.name = "",
       .help = "",
       .group = kMethod,
       .value = MethodTableOptions<ElasticOptions>{false}},
      // A run's option, not a frame's (pipeline/run_options.h window_option).
      {.name = "window",
       .help = "",
       .group = kMethod,
       .value = RunTableOption{&window_option},
       .type_name = "N",
       .method = "elastic"},
      {.name = "window-ends",
       .help = "",
       .group = kMethod,
       .value = RunTableOption{&window_ends_option},
       .method = "elastic"},
      {.name = "", .help = "", .group = kMethod, .value = MethodTableOptions<PaperOptions>{false}},
  };
}

std::vector<CommandOption> run() {
  return {
      {.name = "threads",
       .help = "Frames processed at once; 0 = every core this task may use (its CPU affinity)",
       .group = kRun,
       .value = NumberOption<C, unsigned>{&C::threads, 0u, 1024u},
       .short_name = "j",
       .show_default = true},
      {.name = "frames",
       .help = "Only the frames whose file names carry these numbers (name.0042.obj -> 42): "
               "1-100, 1-100:5 (every 5th), 3,7,12-20; ranges past the frames given are clamped",
       .group = kRun,
       .value = TextOption{&C::frame_ranges},
       .type_name = "RANGES"},
      {.name = "keep-going",
       .help = "Write every good frame and name every bad one, instead of stopping at the first "
               "(exit code: the first bad frame's)",
       .group = kRun,
       .value = FlagOption{&C::keep_going}},
      {.name = "require-converged",
       .help = "Fail a frame (exit 5, naming frame and patch) when a patch's elastic slide did "
               "not converge, instead of writing it and logging 'not converged'",
       .group = kRun,
       .value = FlagOption{&C::require_converged}},
      {.name = "no-slide",
       .help = "Read, check and write every frame unchanged, without sliding (no --patch "
               "needed): the I/O floor of a run, or a sequence converted into a cache (--format "
               "pc2)",
       .group = kRun,
       .value = FlagOption{&C::no_slide}},
      {.name = "quiet",
       .help = "Errors only (not with --verbose)",
       .group = kRun,
       .value = FlagOption{&C::quiet},
       .short_name = "q",
       .excludes = {"--verbose"}},
      {.name = "verbose",
       .help = "Per-patch detail (not with --quiet)",
       .group = kRun,
       .value = FlagOption{&C::verbose},
       .short_name = "v"},
      {.name = "config",
       .help = "Read options from a TOML or INI file (`density = \"paper\"`); the command line "
               "overrides it",
       .group = kRun,
       .value = ConfigFileOption{},
       .type_name = "FILE",
       .check = PathCheck::ExistingFile},
      {.name = "help",
       .help = "Print this help and exit",
       .group = kRun,
       .value = HelpFlag{},
       .short_name = "h"},
      {.name = "version",
       .help = "Print the version and exit",
       .group = kRun,
       .value = VersionFlag{}},
  };
}

std::vector<CommandOption> controls_and_research() {
  return {
      {.name = "weights",
       .help = "Slide weights in [0,1]: one a line in vertex order, or 'index weight' pairs "
               "(unlisted = 0); a vertex of weight w slides w of its way (elastic: in the chart, "
               "staying on the surface; paper: lerp(frame, slid, w) in 3D)",
       .group = kControls,
       .value = TextOption{&C::weights},
       .type_name = "FILE"},
      {.name = "weights-from-obj-color",
       .help = "Slide weights from the bind OBJ's vertex colours (v x y z r g b, or r g b a: "
               "alpha ignored), this channel",
       .group = kControls,
       .value = TextOption{&C::weights_from_obj_color, {"r", "g", "b"}},
       .excludes = {"--weights"}},
      {.name = "weights-from-gltf-attribute",
       .help = "Slide weights from this vertex attribute of the bind glTF's mesh (e.g. "
               "_SLIDE_WEIGHT): SCALAR float, or normalized unsigned byte/short, on every "
               "triangle primitive; a welded vertex takes its first raw copy's weight",
       .group = kControls,
       .value = TextOption{&C::weights_from_gltf_attribute},
       .type_name = "NAME",
       .excludes = {"--weights", "--weights-from-obj-color"}},
      {.name = "strength",
       .help = "",
       .group = kControls,
       .value = RunTableOption{&strength_option}},
      {.name = "pin",
       .help = "Vertex ids that do not slide (12, 12-40, pBody.vtx[12:40]); the skin around "
               "them does",
       .group = kControls,
       .value = TextOption{&C::pin},
       .type_name = "FILE"},
      {.name = "corners",
       .help = "Paper: four vertex ids on a patch's boundary loop, in walking order, for the "
               "square's corners (0,0) (1,0) (1,1) (0,1); that loop becomes the outer loop "
               "(repeatable: one per patch)",
       .group = kControls,
       .value = TextListOption{&C::corners},
       .type_name = "A,B,C,D",
       .method = "paper"},  // the elastic chart is a disk
      {.name = "outer-loop-vertex",
       .help = "A vertex id on the boundary loop to put on the outer border (the elastic "
               "chart's circle, the paper's square; repeatable: one per patch)",
       .group = kControls,
       .value = IndexListOption{&C::outer_loop_vertices, 0, 2147483647},
       .type_name = "V"},
      {.name = "report",
       .help = "Write a JSON report: per frame and patch the method's figures (elastic: energy, "
               "steps; paper: CG, location), slide and edge-spread figures, totals and timings",
       .group = kControls,
       .value = TextOption{&C::report},
       .type_name = "FILE.json"},
      {.name = "report-no-timings",
       .help = "Leave the timings out of the --report (it then depends on the inputs only)",
       .group = kControls,
       .value = FlagOption{&C::report_no_timings},
       .needs = {"--report"}},
      // The solvers' internals, last in --help: no choice a user makes.
      {.name = "",
       .help = "",
       .group = kResearchGroup,
       .value = MethodTableOptions<ElasticOptions>{true}},
      {.name = "",
       .help = "",
       .group = kResearchGroup,
       .value = MethodTableOptions<PaperOptions>{true}},
  };
}

}  // namespace

const std::vector<CommandOption>& command_option_table() {
  static const std::vector<CommandOption> table = [] {
    std::vector<CommandOption> all;
    for (auto part : {inputs_and_gltf(), outputs_and_method(), run(), controls_and_research()})
      for (CommandOption& option : part) all.push_back(std::move(option));
    return all;
  }();
  return table;
}

}  // namespace skinslide
