#include "command_line.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/version.h"

namespace skinslide::cli {
namespace {

namespace fs = std::filesystem;

const char* const kDescription =
    ": skin sliding for deformed character meshes.\n"
    "Moves each patch's free vertices along the frame's surface so that the skin's bind edge "
    "lengths\n"
    "come back: by default (--method elastic) they relax in a fixed chart of the patch towards "
    "the\n"
    "bind's shape with fold-free, energy-decreasing steps; --method paper flattens bind and frame "
    "with\n"
    "force-density bar nets (Yang & Zhang 2010). The patch border and holes never move.\n"
    "Patch files list 0-based face ids of the bind (OBJ `f` lines in file order): `12`, `12-40`,\n"
    "`pBody.f[12:40]`; whitespace or commas between them, `#` comments. For .gltf/.glb the faces\n"
    "are the triangles of the mesh's triangle primitives, in primitive order (vertices welded by\n"
    "position for connectivity only).\n"
    "A rigged glTF character can be its own frame source:\n"
    "  skinslide --patch P.txt --animation NAME|INDEX [--fps N | --keyframes] character.glb\n"
    "A point cache (.pc2, .mdd) of the bind's vertices is a whole shot: one FRAME, slid sample by\n"
    "sample into a cache of the same name (a --frames chunk: <shot>.<first>-<last>.pc2); chunks\n"
    "join with\n"
    "  skinslide join [-o DIR] CHUNK...\n"
    "Two slid outputs (folders of frames, or caches) compare as meshes, for CI, with\n"
    "  skinslide compare [--tolerance T] A B";

// Inputs and glTF.
void add_inputs(CLI::App& app, CliOptions& o) {
  const char* in = "Inputs";
  app.add_option("--patch", o.run.patches,
                 "Patch file (repeatable; each file's patches are separate)")
      ->required()
      ->allow_extra_args(false)
      ->type_name("FILE")
      ->group(in);
  app.add_option("bind", o.run.bind, "Bind mesh (.obj, .gltf, .glb)")
      ->required()
      ->type_name("BIND")
      ->group(in);
  auto* frames =
      app.add_option("frames", o.run.frames,
                     "Deformed frames: the bind mesh with moved vertices, or one point cache of "
                     "them (.pc2, .mdd); none with --animation")
          ->type_name("FRAME...")
          ->group(in);
  const char* gl = "glTF";
  app.add_option("--mesh", o.run.mesh, "Mesh of a .gltf/.glb holding several (name, else index)")
      ->type_name("NAME|INDEX")
      ->group(gl);
  auto* anim = app.add_option("--animation", o.rig.animation,
                              "BIND is an animated glTF character (skin and/or morph targets): "
                              "pose it at each sampled time of this clip (name, else index) and "
                              "slide those frames")
                   ->type_name("NAME|INDEX")
                   ->excludes(frames)
                   ->group(gl);
  auto* fps = app.add_option("--fps", o.rig.fps,
                             "Sample the clip every 1/N s from its first key to its last")
                  ->check(CLI::Range(0.001, 100000.0))
                  ->type_name("N")
                  ->needs(anim)
                  ->group(gl);
  app.add_flag("--keyframes", o.keyframes, "Sample the clip at its key times (the default)")
      ->needs(anim)
      ->excludes(fps)
      ->group(gl);
  app.add_option("--format", o.run.format,
                 "Format of the slid frames of --animation (default glb; frames "
                 "<character>.<frame>.<format> from 0000) or of a point cache FRAME (default its "
                 "own): obj or glb, a file a frame; pc2 or mdd, one cache")
      ->check(CLI::IsMember({"obj", "glb", "pc2", "mdd"}))
      ->group(gl);
}

void add_outputs(CLI::App& app, CliOptions& o) {
  const char* out = "Output";
  app.add_option("-o,--output", o.run.output, "Folder for the slid frames (same file names)")
      ->capture_default_str()
      ->type_name("DIR")
      ->group(out);
  app.add_option("--dump", o.run.dump_dir,
                 "Folder for EXR images of each patch's nets: ID lookup image and geometry image "
                 "(P, coverage, slide field), for the bind and every frame (off by default)")
      ->type_name("DIR")
      ->group(out);
  app.add_option("--preview", o.run.preview_dir,
                 "Folder for a PNG per frame and patch: bind net and frame net drawn over each "
                 "other, slides marked (off by default)")
      ->type_name("DIR")
      ->group(out);
  app.add_option("--preview-size", o.run.preview_size, "Side of the preview PNGs, pixels")
      ->capture_default_str()
      ->check(CLI::Range(16, 8192))
      ->group(out);
}

void add_method(CLI::App& app, CliOptions& o) {
  const char* method = "Method";
  app.add_option("--method", o.method,
                 "elastic: the free vertices relax in a fixed chart of each patch towards the "
                 "bind's edge lengths, with fold-free, energy-decreasing steps; paper: Yang & "
                 "Zhang's bar nets (the options below --tolerance)")
      ->capture_default_str()
      ->check(CLI::IsMember({"elastic", "paper"}))
      ->group(method);
  app.add_option("--rotation-fits", o.elastic.rotation_fits,
                 "Elastic: ARAP local/global rounds (fit each triangle's rotation, then relax with "
                 "them held); more reach lower energies, fewer pop less from frame to frame")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000))
      ->group(method);
  app.add_option("--max-iterations", o.elastic.max_iterations,
                 "Elastic: Gauss-Newton steps per round at most")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000))
      ->group(method);
  app.add_option("--tolerance", o.elastic.tolerance,
                 "Elastic: a round stops at the first step that lowers its energy by less than "
                 "this fraction of its starting energy")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0))
      ->group(method);
  app.add_option("--density", o.density,
                 "Paper: force density q of a bar of length L: paper = 1 - L/Lmax (floored), "
                 "inverse|length = Lmin/L, uniform = 1")
      ->capture_default_str()
      ->check(CLI::IsMember({"paper", "inverse", "length", "uniform"}))
      ->group(method);
  app.add_option("--holes", o.holes,
                 "Paper: inner boundary loops in the bind net: free (the paper) or fill (a "
                 "virtual centre node per hole)")
      ->capture_default_str()
      ->check(CLI::IsMember({"free", "fill"}))
      ->group(method);
  app.add_option("--q-floor", o.paper.q_floor,
                 "Paper: smallest force density (densities paper, inverse)")
      ->capture_default_str()
      ->check(CLI::Range(1e-12, 1.0))
      ->group(method);
  app.add_option("--frame-solver", o.frame_solver,
                 "Paper: how bind and frame nets are solved: cholesky (sparse factor, analysis "
                 "reused by every frame), multigrid (conjugate gradient preconditioned by an "
                 "aggregation multigrid; no ordering, so a shorter set-up, and faster frames on "
                 "large patches), auto (multigrid for patches of " +
                     std::to_string(kMultigridFreeNodes) +
                     " free vertices or more, else cholesky) or cg (frame nets by "
                     "Jacobi-preconditioned CG; slow, for comparison). The nets agree within "
                     "--cg-tolerance")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "cholesky", "multigrid", "cg"}))
      ->group(method);
  app.add_option("--cg-tolerance", o.paper.cg_tolerance,
                 "Paper: CG (multigrid, cg) stops at |r| <= tol |b|; every method keeps a "
                 "frame's warm start that meets it")
      ->capture_default_str()
      ->check(CLI::Range(1e-16, 1e-2))
      ->group(method);
  app.add_option("--cg-max-iterations", o.paper.cg_max_iterations,
                 "Paper: past this the frame net is solved directly (counted)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000))
      ->group(method);
  app.add_option("--locate", o.locate,
                 "Paper: finding bind positions in frame nets: walk (from each vertex's own "
                 "triangles) or image (a triangle-ID image, --lookup-size)")
      ->capture_default_str()
      ->check(CLI::IsMember({"walk", "image"}))
      ->group(method);
  app.add_option("--lookup-size", o.paper.lookup_size,
                 "Side of the triangle-ID images (--locate image, --dump), pixels")
      ->capture_default_str()
      ->check(CLI::Range(8, 16384))
      ->group(method);
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
  app.add_flag("--no-slide", o.run.no_slide,
               "Read, check and write every frame unchanged, without sliding: the I/O floor of a "
               "run, for timing")
      ->group(run);
  app.add_flag("-q,--quiet", o.quiet, "Errors only")->group(run);
  app.add_flag("-v,--verbose", o.verbose, "Per-patch detail")->group(run);
  app.get_option("--quiet")->excludes("--verbose");
  app.set_config("--config", "",
                 "Read options from a TOML or INI file (`density = \"paper\"`); "
                 "the command line overrides it")
      ->type_name("FILE")
      ->check(CLI::ExistingFile)
      ->group(run);
}

// Controls and the report.
void add_controls(CLI::App& app, CliOptions& o) {
  const char* controls = "Controls";
  auto* weights =
      app.add_option("--weights", o.run.weights,
                     "Slide weights in [0,1]: one a line in vertex order, or 'index weight' pairs "
                     "(unlisted = 0); output = lerp(frame, slid, weight)")
          ->type_name("FILE")
          ->group(controls);
  app.add_option("--weights-from-obj-color", o.run.weights_from_obj_color,
                 "Slide weights from the bind OBJ's vertex colours (v x y z r g b), this channel")
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
  app.add_option("--strength", o.run.strength,
                 "Multiplies every slide weight; the product is clamped to [0,1]")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6))
      ->group(controls);
  app.add_option("--pin", o.run.pin,
                 "Vertex ids that do not slide (12, 12-40, pBody.vtx[12:40]); the skin around "
                 "them does")
      ->type_name("FILE")
      ->group(controls);
  app.add_option("--corners", o.run.corners,
                 "Four vertex ids on a patch's boundary loop, in walking order, for the square's "
                 "corners (0,0) (1,0) (1,1) (0,1); that loop becomes the outer loop (repeatable: "
                 "one per patch)")
      ->type_name("A,B,C,D")
      ->allow_extra_args(false)
      ->group(controls);
  app.add_option("--outer-loop-vertex", o.run.outer_loop_vertices,
                 "A vertex id on the boundary loop to put on the square (repeatable: one per "
                 "patch)")
      ->type_name("V")
      ->allow_extra_args(false)
      ->check(CLI::Range(0, 2147483647))
      ->group(controls);
  auto* report = app.add_option("--report", o.run.report,
                                "Write a JSON report: per frame and patch CG, location, slide and "
                                "edge-spread figures, totals and timings")
                     ->type_name("FILE.json")
                     ->group(controls);
  app.add_flag("--report-no-timings", o.report_no_timings,
               "Leave the timings out of the report (it then depends on the inputs only)")
      ->needs(report)
      ->group(controls);
}

}  // namespace

std::string description() { return "skinslide " + std::string(version()) + kDescription; }

void add_options(CLI::App& app, CliOptions& o) {
  add_inputs(app, o);
  add_outputs(app, o);
  add_method(app, o);
  add_run(app, o);
  add_controls(app, o);
}

void check_options(const CLI::App& app, CliOptions& o) {
  o.has_rig = app.count("--animation") > 0;
  // Options of one method only are refused with the other, naming both.
  const bool paper = o.method == "paper";
  for (const char* name : {"--density", "--holes", "--q-floor", "--frame-solver", "--cg-tolerance",
                           "--cg-max-iterations", "--locate", "--corners"})
    if (paper == false && app.count(name) > 0)
      throw CLI::ValidationError(name, std::string("applies to --method paper only, not to "
                                                   "--method elastic"));
  for (const char* name : {"--rotation-fits", "--max-iterations", "--tolerance"})
    if (paper && app.count(name) > 0)
      throw CLI::ValidationError(name, std::string("applies to --method elastic only, not to "
                                                   "--method paper"));
  const RunOptions& r = o.run;
  if (r.no_slide &&
      (o.has_rig || !r.report.empty() || !r.dump_dir.empty() || !r.preview_dir.empty()))
    throw CLI::ValidationError(
        "--no-slide",
        "copies frame files only: not with --animation, --report, --dump or --preview");
  if (!o.has_rig && r.frames.empty())
    throw CLI::ValidationError("FRAME...",
                               "give at least one FRAME, or --animation with a rigged glTF BIND");
  const bool cache_frame = r.frames.size() == 1 && cache_format(r.frames.front());
  if (app.count("--format") > 0 && !o.has_rig && !cache_frame)
    throw CLI::ValidationError("--format",
                               "applies to --animation or a point cache FRAME (.pc2, .mdd)");
  std::string ext = fs::path(r.bind).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
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

RunOptions run_options(const CliOptions& o) {
  RunOptions r = o.run;
  if (o.has_rig) r.rig = o.rig;
  r.report_timings = !o.report_no_timings;
  r.lookup_size = o.paper.lookup_size;
  r.slide = parse_method(o.method);
  if (std::holds_alternative<ElasticOptions>(r.slide)) {
    r.slide = o.elastic;
  } else {
    PaperOptions paper = o.paper;
    paper.density = parse_density(o.density);
    paper.holes = parse_holes(o.holes);
    paper.frame_solver = parse_frame_solver(o.frame_solver);
    paper.locate = parse_locate(o.locate);
    r.slide = paper;
  }
  return r;
}

}  // namespace skinslide::cli
