// skinslide: skin sliding after any deformer (Yang & Zhang 2010), a batch command.
// The command line only: CLI11 options -> RunOptions -> run() (pipeline/run.h, which reads the
// bind and the patches once, then slides every frame) -> exit code. What the run tells goes to
// stderr here: a line per frame in frame order, or a progress line on a terminal.

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <clocale>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/allocator.h"
#include "core/error.h"
#include "core/version.h"
#include "io/atomic_write.h"
#include "io/point_cache.h"
#include "join.h"
#include "pipeline/run.h"
#include "progress.h"

namespace fs = std::filesystem;
using namespace skinslide;

namespace {

struct CliOptions {
  std::vector<std::string> patches;
  std::string bind;
  std::vector<std::string> frames;
  std::string output = "slid";
  std::string dump_dir;     // --dump: EXR images of the nets; empty = none
  std::string preview_dir;  // --preview: PNG pictures of the nets; empty = none
  int preview_size = 1024;
  std::string method = "elastic";
  int rotation_fits = ElasticOptions{}.rotation_fits;
  int max_iterations = ElasticOptions{}.max_iterations;
  double tolerance = ElasticOptions{}.tolerance;
  std::string density = "inverse";
  std::string holes = "fill";
  double q_floor = 1e-3;
  std::string frame_solver = "auto";
  double cg_tolerance = 1e-12;
  int cg_max_iterations = 2000;
  std::string locate = "walk";
  int lookup_size = 1024;
  unsigned threads = 0;
  std::string frame_ranges;  // --frames: empty = every frame
  bool keep_going = false;
  bool quiet = false;
  bool verbose = false;
  bool no_slide = false;
  std::string mesh;        // glTF: which mesh (name or index); empty = the only one
  bool rig = false;        // --animation given: the frames are BIND posed by its skin
  std::string animation;   // clip name or index
  double fps = 0;          // 0 = the clip's key times
  bool keyframes = false;  // --keyframes: the default, spelled out
  std::string format;      // of the slid frames: obj, glb, pc2, mdd; empty = the source's
  // Controls (README "Controls")
  std::string weights;
  std::string weights_color;
  std::string weights_attribute;  // glTF vertex attribute of the bind's mesh
  double strength = 1;
  std::string pin;
  std::vector<std::string> corners;
  std::vector<int> outer_loop_vertices;
  std::string report;
  bool report_no_timings = false;
};

// The command line's options as the pipeline's. \throw Error(Usage) on an unknown method name.
RunOptions run_options(const CliOptions& o) {
  RunOptions r;
  r.bind = o.bind;
  r.patches = o.patches;
  r.frames = o.frames;
  r.mesh = o.mesh;
  if (o.rig) r.rig = RigOptions{o.animation, o.fps};
  r.format = o.format;
  r.output = o.output;
  r.dump_dir = o.dump_dir;
  r.preview_dir = o.preview_dir;
  r.preview_size = o.preview_size;
  r.report = o.report;
  r.report_timings = !o.report_no_timings;
  SlideOptions& s = r.slide;
  s.method = parse_method(o.method);
  s.elastic.rotation_fits = o.rotation_fits;
  s.elastic.max_iterations = o.max_iterations;
  s.elastic.tolerance = o.tolerance;
  s.density = parse_density(o.density);
  s.holes = parse_holes(o.holes);
  s.q_floor = o.q_floor;
  s.frame_solver = parse_frame_solver(o.frame_solver);
  s.cg_tolerance = o.cg_tolerance;
  s.cg_max_iterations = o.cg_max_iterations;
  s.locate = parse_locate(o.locate);
  s.lookup_size = o.lookup_size;
  r.weights = o.weights;
  r.weights_from_obj_color = o.weights_color;
  r.weights_from_gltf_attribute = o.weights_attribute;
  r.strength = o.strength;
  r.pin = o.pin;
  r.corners = o.corners;
  r.outer_loop_vertices.assign(o.outer_loop_vertices.begin(), o.outer_loop_vertices.end());
  r.threads = o.threads;
  r.frame_ranges = o.frame_ranges;
  r.keep_going = o.keep_going;
  r.no_slide = o.no_slide;
  return r;
}

// Runs the pipeline, printing what it tells to stderr as -q/-v ask; returns the exit code.
int run_and_print(const CliOptions& o) {
  const cli::Verbosity verbosity =
      o.quiet ? cli::Verbosity::Quiet
              : (o.verbose ? cli::Verbosity::Verbose : cli::Verbosity::Normal);
  const auto shown = [&](LogLevel level) {
    return level == LogLevel::Error ||
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
  const RunResult result = skinslide::run(run_options(o), events);
  const size_t failed = result.failures.size();
  if (verbosity != cli::Verbosity::Quiet || failed > 0)
    std::fprintf(stderr, "skinslide: %zu frames %s%s in %.2f s -> %s\n", result.frames - failed,
                 o.no_slide ? "copied" : "slid",
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
  CliOptions o;
  CLI::App app{
      "skinslide " + std::string(version()) +
          ": skin sliding for deformed character meshes.\n"
          "Moves each patch's free vertices along the frame's surface so that the skin's bind "
          "edge lengths\n"
          "come back: by default (--method elastic) they relax in a fixed chart of the patch "
          "towards the\n"
          "bind's shape with fold-free, energy-decreasing steps; --method paper flattens bind and "
          "frame with\n"
          "force-density bar nets (Yang & Zhang 2010). The patch border and holes never move.\n"
          "Patch files list 0-based face ids of the bind (OBJ `f` lines in file order): `12`, "
          "`12-40`,\n"
          "`pBody.f[12:40]`; whitespace or commas between them, `#` comments. For .gltf/.glb the "
          "faces\n"
          "are the triangles of the mesh's triangle primitives, in primitive order (vertices "
          "welded by\n"
          "position for connectivity only).\n"
          "A rigged glTF character can be its own frame source:\n"
          "  skinslide --patch P.txt --animation NAME|INDEX [--fps N | --keyframes] character.glb\n"
          "A point cache (.pc2, .mdd) of the bind's vertices is a whole shot: one FRAME, slid "
          "sample by\n"
          "sample into a cache of the same name (a --frames chunk: <shot>.<first>-<last>.pc2); "
          "chunks join with\n"
          "  skinslide join [-o DIR] CHUNK...",
      "skinslide"};
  app.set_version_flag("--version", std::string("skinslide ") + version());
  app.get_formatter()->column_width(36);

  auto* in = "Inputs";
  app.add_option("--patch", o.patches, "Patch file (repeatable; each file's patches are separate)")
      ->required()
      ->allow_extra_args(false)
      ->type_name("FILE")
      ->group(in);
  app.add_option("bind", o.bind, "Bind mesh (.obj, .gltf, .glb)")
      ->required()
      ->type_name("BIND")
      ->group(in);
  auto* frames_opt =
      app.add_option("frames", o.frames,
                     "Deformed frames: the bind mesh with moved vertices, or one point cache of "
                     "them (.pc2, .mdd); none with --animation")
          ->type_name("FRAME...")
          ->group(in);

  auto* gl = "glTF";
  app.add_option("--mesh", o.mesh, "Mesh of a .gltf/.glb holding several (name, else index)")
      ->type_name("NAME|INDEX")
      ->group(gl);
  auto* anim =
      app.add_option("--animation", o.animation,
                     "BIND is an animated glTF character (skin and/or morph targets): pose "
                     "it at each sampled time of this clip (name, else index) and slide "
                     "those frames")
          ->type_name("NAME|INDEX")
          ->excludes(frames_opt)
          ->group(gl);
  auto* fps =
      app.add_option("--fps", o.fps, "Sample the clip every 1/N s from its first key to its last")
          ->check(CLI::Range(0.001, 100000.0))
          ->type_name("N")
          ->needs(anim)
          ->group(gl);
  app.add_flag("--keyframes", o.keyframes, "Sample the clip at its key times (the default)")
      ->needs(anim)
      ->excludes(fps)
      ->group(gl);
  auto* format =
      app.add_option("--format", o.format,
                     "Format of the slid frames of --animation (default glb; frames "
                     "<character>.<frame>.<format> from 0000) or of a point cache FRAME (default "
                     "its own): obj or glb, a file a frame; pc2 or mdd, one cache")
          ->check(CLI::IsMember({"obj", "glb", "pc2", "mdd"}))
          ->group(gl);

  auto* out = "Output";
  app.add_option("-o,--output", o.output, "Folder for the slid frames (same file names)")
      ->capture_default_str()
      ->type_name("DIR")
      ->group(out);

  app.add_option("--dump", o.dump_dir,
                 "Folder for EXR images of each patch's nets: ID lookup image and geometry image "
                 "(P, coverage, slide field), for the bind and every frame (off by default)")
      ->type_name("DIR")
      ->group(out);
  app.add_option("--preview", o.preview_dir,
                 "Folder for a PNG per frame and patch: bind net and frame net drawn over each "
                 "other, slides marked (off by default)")
      ->type_name("DIR")
      ->group(out);
  app.add_option("--preview-size", o.preview_size, "Side of the preview PNGs, pixels")
      ->capture_default_str()
      ->check(CLI::Range(16, 8192))
      ->group(out);

  auto* method = "Method";
  app.add_option("--method", o.method,
                 "elastic: the free vertices relax in a fixed chart of each patch towards the "
                 "bind's edge lengths, with fold-free, energy-decreasing steps; paper: Yang & "
                 "Zhang's bar nets (the options below --tolerance)")
      ->capture_default_str()
      ->check(CLI::IsMember({"elastic", "paper"}))
      ->group(method);
  app.add_option("--rotation-fits", o.rotation_fits,
                 "Elastic: ARAP local/global rounds (fit each triangle's rotation, then relax with "
                 "them held); more reach lower energies, fewer pop less from frame to frame")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000))
      ->group(method);
  app.add_option("--max-iterations", o.max_iterations,
                 "Elastic: Gauss-Newton steps per round at most")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000))
      ->group(method);
  app.add_option("--tolerance", o.tolerance,
                 "Elastic: a round stops at the first step that lowers its energy by less than "
                 "this fraction of its starting energy")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0))
      ->group(method);
  app.add_option("--density", o.density,
                 "Paper: force density q of a bar of length L: paper = 1 - L/Lmax (floored), "
                 "inverse|length "
                 "= Lmin/L, uniform = 1")
      ->capture_default_str()
      ->check(CLI::IsMember({"paper", "inverse", "length", "uniform"}))
      ->group(method);
  app.add_option(
         "--holes", o.holes,
         "Paper: inner boundary loops in the bind net: free (the paper) or fill (a virtual centre "
         "node per hole)")
      ->capture_default_str()
      ->check(CLI::IsMember({"free", "fill"}))
      ->group(method);
  app.add_option("--q-floor", o.q_floor, "Paper: smallest force density (densities paper, inverse)")
      ->capture_default_str()
      ->check(CLI::Range(1e-12, 1.0))
      ->group(method);
  const std::string solver_help =
      "Paper: how bind and frame nets are solved: cholesky (sparse factor, analysis reused by "
      "every "
      "frame), multigrid (conjugate gradient preconditioned by an aggregation multigrid; no "
      "ordering, so a shorter set-up, and faster frames on large patches), auto (multigrid for "
      "patches of " +
      std::to_string(kMultigridFreeNodes) +
      " free vertices or more, else cholesky) or cg (frame nets by Jacobi-preconditioned CG; "
      "slow, for comparison). The nets agree within --cg-tolerance";
  app.add_option("--frame-solver", o.frame_solver, solver_help)
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "cholesky", "multigrid", "cg"}))
      ->group(method);
  app.add_option(
         "--cg-tolerance", o.cg_tolerance,
         "Paper: CG (multigrid, cg) stops at |r| <= tol |b|; every method keeps a frame's warm "
         "start that meets it")
      ->capture_default_str()
      ->check(CLI::Range(1e-16, 1e-2))
      ->group(method);
  app.add_option("--cg-max-iterations", o.cg_max_iterations,
                 "Paper: past this the frame net is solved directly (counted)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000))
      ->group(method);
  app.add_option(
         "--locate", o.locate,
         "Paper: finding bind positions in frame nets: walk (from each vertex's own triangles) or "
         "image (a triangle-ID image, --lookup-size)")
      ->capture_default_str()
      ->check(CLI::IsMember({"walk", "image"}))
      ->group(method);
  app.add_option("--lookup-size", o.lookup_size,
                 "Side of the triangle-ID images (--locate image, --dump), pixels")
      ->capture_default_str()
      ->check(CLI::Range(8, 16384))
      ->group(method);

  auto* run_group = "Run";
  app.add_option("-j,--threads", o.threads,
                 "Frames processed at once; 0 = every core this task may use (its CPU affinity)")
      ->capture_default_str()
      ->check(CLI::Range(0u, 1024u))
      ->group(run_group);
  app.add_option("--frames", o.frame_ranges,
                 "Only the frames whose file names carry these numbers (name.0042.obj -> 42): "
                 "1-100, 1-100:5 (every 5th), 3,7,12-20; ranges past the frames given are clamped")
      ->type_name("RANGES")
      ->group(run_group);
  app.add_flag("--keep-going", o.keep_going,
               "Write every good frame and name every bad one, instead of stopping at the first "
               "(exit code: the first bad frame's)")
      ->group(run_group);
  app.add_flag("--no-slide", o.no_slide,
               "Read, check and write every frame unchanged, without sliding: the I/O floor of a "
               "run, for timing")
      ->group(run_group);
  app.add_flag("-q,--quiet", o.quiet, "Errors only")->group(run_group);
  app.add_flag("-v,--verbose", o.verbose, "Per-patch detail")->group(run_group);
  app.get_option("--quiet")->excludes("--verbose");
  app.set_config("--config", "",
                 "Read options from a TOML or INI file (`density = \"paper\"`); "
                 "the command line overrides it")
      ->type_name("FILE")
      ->check(CLI::ExistingFile)
      ->group(run_group);

  auto* controls = "Controls";
  auto* weights =
      app.add_option("--weights", o.weights,
                     "Slide weights in [0,1]: one a line in vertex order, or 'index weight' pairs "
                     "(unlisted = 0); output = lerp(frame, slid, weight)")
          ->type_name("FILE")
          ->group(controls);
  app.add_option("--weights-from-obj-color", o.weights_color,
                 "Slide weights from the bind OBJ's vertex colours (v x y z r g b), this channel")
      ->check(CLI::IsMember({"r", "g", "b"}))
      ->excludes(weights)
      ->group(controls);
  auto* weights_attribute =
      app.add_option("--weights-from-gltf-attribute", o.weights_attribute,
                     "Slide weights from this vertex attribute of the bind glTF's mesh (e.g. "
                     "_SLIDE_WEIGHT): SCALAR float, or normalized unsigned byte/short, on every "
                     "triangle primitive; a welded vertex takes its first raw copy's weight")
          ->type_name("NAME")
          ->excludes(weights)
          ->excludes("--weights-from-obj-color")
          ->group(controls);
  app.add_option("--strength", o.strength,
                 "Multiplies every slide weight; the product is clamped to [0,1]")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6))
      ->group(controls);
  app.add_option("--pin", o.pin,
                 "Vertex ids that do not slide (12, 12-40, pBody.vtx[12:40]); the skin around "
                 "them does")
      ->type_name("FILE")
      ->group(controls);
  app.add_option("--corners", o.corners,
                 "Four vertex ids on a patch's boundary loop, in walking order, for the square's "
                 "corners (0,0) (1,0) (1,1) (0,1); that loop becomes the outer loop (repeatable: "
                 "one per patch)")
      ->type_name("A,B,C,D")
      ->allow_extra_args(false)
      ->group(controls);
  app.add_option(
         "--outer-loop-vertex", o.outer_loop_vertices,
         "A vertex id on the boundary loop to put on the square (repeatable: one per patch)")
      ->type_name("V")
      ->allow_extra_args(false)
      ->check(CLI::Range(0, 2147483647))
      ->group(controls);
  auto* report_opt =
      app.add_option("--report", o.report,
                     "Write a JSON report: per frame and patch CG, location, slide and edge-spread "
                     "figures, totals and timings")
          ->type_name("FILE.json")
          ->group(controls);
  app.add_flag("--report-no-timings", o.report_no_timings,
               "Leave the timings out of the report (it then depends on the inputs only)")
      ->needs(report_opt)
      ->group(controls);

  try {
    app.parse(argc, argv);
    o.rig = anim->count() > 0;
    // Options of one method only are refused with the other, naming both.
    const bool paper = o.method == "paper";
    for (const char* name : {"--density", "--holes", "--q-floor", "--frame-solver",
                             "--cg-tolerance", "--cg-max-iterations", "--locate", "--corners"})
      if (paper == false && app.count(name) > 0)
        throw CLI::ValidationError(name, std::string("applies to --method paper only, not to "
                                                     "--method elastic"));
    for (const char* name : {"--rotation-fits", "--max-iterations", "--tolerance"})
      if (paper && app.count(name) > 0)
        throw CLI::ValidationError(name, std::string("applies to --method elastic only, not to "
                                                     "--method paper"));
    if (o.no_slide && (o.rig || !o.report.empty() || !o.dump_dir.empty() || !o.preview_dir.empty()))
      throw CLI::ValidationError(
          "--no-slide",
          "copies frame files only: not with --animation, --report, --dump or --preview");
    if (!o.rig && o.frames.empty())
      throw CLI::ValidationError("FRAME...",
                                 "give at least one FRAME, or --animation with a rigged glTF BIND");
    const bool cache_frame = o.frames.size() == 1 && cache_format(o.frames.front());
    if (format->count() > 0 && !o.rig && !cache_frame)
      throw CLI::ValidationError("--format",
                                 "applies to --animation or a point cache FRAME (.pc2, .mdd)");
    std::string ext = fs::path(o.bind).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    const bool gltf_bind = ext == ".gltf" || ext == ".glb";
    if (o.rig && !gltf_bind)
      throw CLI::ValidationError("--animation", "needs a .gltf or .glb BIND, not " + o.bind);
    if (cache_frame && o.format == "glb" && !gltf_bind)
      throw CLI::ValidationError("--format", "glb from a point cache needs a .gltf or .glb BIND");
    if (weights_attribute->count() > 0 && o.weights_attribute.empty())
      throw CLI::ValidationError("--weights-from-gltf-attribute", "needs an attribute name");
    if (!o.weights_attribute.empty() && !gltf_bind)
      throw CLI::ValidationError("--weights-from-gltf-attribute",
                                 "needs a .gltf or .glb BIND, not " + o.bind);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "skinslide: error: %s\nRun with --help for the options.\n", e.what());
    return exit_code(ErrorKind::Usage);
  }
  try {
    return run_and_print(o);
  } catch (const Error& e) {
    std::fprintf(stderr, "skinslide: error: %s\n", e.what());
    return exit_code(e.kind());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "skinslide: error: out of memory\n");
    return exit_code(ErrorKind::Internal);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "skinslide: internal error: %s\n", e.what());
    return exit_code(ErrorKind::Internal);
  }
}
