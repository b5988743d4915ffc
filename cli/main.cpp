// skinslide: skin sliding after any deformer (Yang & Zhang 2010), a batch command.
// Reads the bind mesh and the patch files once, then slides every frame (in parallel across
// frames only, so the bytes written never depend on the thread count) and writes each slid frame
// as an edited copy of the frame's own file.

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <clocale>
#include <cstdio>
#include <filesystem>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/error.h"
#include "core/version.h"
#include "io/mesh_file.h"
#include "io/number_format.h"
#include "io/patch_file.h"
#include "pipeline/bind_setup.h"
#include "pipeline/slide_frame.h"
#include "progress.h"

namespace fs = std::filesystem;
using namespace skinslide;

namespace {

struct CliOptions {
  std::vector<std::string> patches;
  std::string bind;
  std::vector<std::string> frames;
  std::string output = "slid";
  std::string density = "inverse";
  std::string holes = "fill";
  double q_floor = 1e-3;
  std::string frame_solver = "cholesky";
  double cg_tolerance = 1e-12;
  int cg_max_iterations = 2000;
  std::string locate = "walk";
  int lookup_size = 1024;
  unsigned threads = 0;
  bool quiet = false;
  bool verbose = false;
  bool no_slide = false;
};

std::string fmt(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

// Same file (by identity when it exists, else by normalised path).
bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

// Output paths, one per frame: DIR/<frame file name>. Refuses an output that is an input and two
// frames that would write the same output, before any work is done.
std::vector<std::string> output_paths(const CliOptions& o) {
  std::vector<std::string> inputs = o.frames;
  inputs.push_back(o.bind);
  inputs.insert(inputs.end(), o.patches.begin(), o.patches.end());
  std::vector<std::string> out;
  std::set<std::string> names;
  for (const std::string& f : o.frames) {
    const std::string name = fs::path(f).filename().string();
    if (!names.insert(name).second)
      throw Error(ErrorKind::Usage, "two frames are named '" + name + "'; their outputs in " +
                                        o.output + " would collide");
    const fs::path target = fs::path(o.output) / name;
    for (const std::string& in : inputs)
      if (same_file(target, in))
        throw Error(ErrorKind::Usage, "output " + target.string() + " would overwrite input " + in +
                                          "; choose another --output folder");
    out.push_back(target.string());
  }
  return out;
}

void make_output_dir(const std::string& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw Error(ErrorKind::Output, dir + ": cannot write: exists and is not a folder");
  fs::create_directories(dir, ec);
  if (ec)
    throw Error(ErrorKind::Output, dir + ": cannot create the output folder: " + ec.message());
}

SlideOptions slide_options(const CliOptions& o) {
  SlideOptions s;
  s.density = parse_density(o.density);
  s.holes = parse_holes(o.holes);
  s.q_floor = o.q_floor;
  s.frame_solver = parse_frame_solver(o.frame_solver);
  s.cg_tolerance = o.cg_tolerance;
  s.cg_max_iterations = o.cg_max_iterations;
  s.locate = parse_locate(o.locate);
  s.lookup_size = o.lookup_size;
  return s;
}

struct FrameSummary {
  int cg_iterations = 0;
  int direct_solves = 0;
  bool cholesky = false;
  int fallbacks = 0;
  int net_flips = 0;
  double max_slide = 0;
  size_t moved = 0;
};

FrameSummary summarise(const BindSetup& setup, const FrameResult& r) {
  FrameSummary s;
  s.cholesky = setup.options.frame_solver == FrameSolver::Cholesky;
  for (const PatchFrameReport& p : r.patches) {
    s.cg_iterations = std::max(s.cg_iterations, p.cg_iterations);
    s.direct_solves += p.direct_solve;
    s.fallbacks += p.located_fallback;
    s.net_flips += p.frame_net_flips;
    s.max_slide = std::max(s.max_slide, p.max_slide);
  }
  s.moved = r.slid.vertex.size();
  return s;
}

// Reads, checks, slides and writes one frame; returns the log lines for it.
std::vector<std::string> run_frame(const BindSetup& setup, const MeshFile& bind,
                                   const CliOptions& o, const std::string& frame_path,
                                   const std::string& out_path) {
  const MeshFile frame = read_mesh_file(frame_path);
  require_same_topology(bind, frame);
  if (o.no_slide) {
    write_slid_mesh_file(frame, SlidVertices{}, out_path);
    return {"skinslide: " + frame_path + ": unchanged (--no-slide) -> " + out_path};
  }
  FrameResult result;
  try {
    result = slide_frame(setup, frame.mesh.positions);
  } catch (const Error& e) {
    throw Error(e.kind(), frame_path + ": " + e.what());
  }
  write_slid_mesh_file(frame, result.slid, out_path);
  const FrameSummary s = summarise(setup, result);
  std::vector<std::string> lines;
  lines.push_back(
      "skinslide: " + frame_path + ": " + std::to_string(setup.patches.size()) + " patches, " +
      (s.cholesky ? std::string("Cholesky") : "CG " + std::to_string(s.cg_iterations) + " it") +
      ", max slide " + fmt(s.max_slide) + ", " + std::to_string(s.fallbacks) + " fallbacks -> " +
      out_path);
  if (o.verbose)
    for (size_t p = 0; p < result.patches.size(); ++p) {
      const PatchFrameReport& r = result.patches[p];
      lines.push_back("  patch " + std::to_string(p) + ": " +
                      (setup.patches[p].skipped
                           ? std::string("skipped (all vertices on loops)")
                           : (s.cholesky ? std::string("Cholesky")
                                         : "CG " + std::to_string(r.cg_iterations) +
                                               " it, residual " + fmt(r.cg_residual) +
                                               (r.direct_solve ? " (solved directly)" : "")) +
                                 ", located " + std::to_string(r.located_in_image) + " + " +
                                 std::to_string(r.located_fallback) + " fallback, net flips " +
                                 std::to_string(r.frame_net_flips) + ", slide max " +
                                 fmt(r.max_slide) + " mean " + fmt(r.mean_slide)));
    }
  return lines;
}

int run(const CliOptions& o) {
  const cli::Verbosity verbosity =
      o.quiet ? cli::Verbosity::Quiet
              : (o.verbose ? cli::Verbosity::Verbose : cli::Verbosity::Normal);
  const SlideOptions options = slide_options(o);
  const std::vector<std::string> outputs = output_paths(o);

  const MeshFile bind = read_mesh_file(o.bind);
  std::vector<std::vector<Index>> selections;
  for (const std::string& p : o.patches)
    selections.push_back(selected_faces(read_patch(p), bind.mesh.face_count()));
  // --no-slide measures the I/O floor of a run: no bind set-up, frames copied unchanged.
  const BindSetup setup =
      o.no_slide ? BindSetup{} : bind_setup(bind.mesh, selections, options, [&](Index f) {
        return "face " + std::to_string(f) + " (" + bind.where_face(f) + ")";
      });
  size_t sliding = 0;
  for (const PatchNet& p : setup.patches) sliding += p.free_vertices.size();
  if (o.no_slide && verbosity != cli::Verbosity::Quiet)
    std::fprintf(stderr,
                 "skinslide: %s: --no-slide: frames are read, checked and written unchanged\n",
                 o.bind.c_str());
  else if (verbosity != cli::Verbosity::Quiet)
    std::fprintf(stderr,
                 "skinslide: %s: %zu patches, %zu sliding vertices (density %s, holes %s)\n",
                 o.bind.c_str(), setup.patches.size(), sliding, to_string(options.density).c_str(),
                 to_string(options.holes).c_str());
  if (verbosity == cli::Verbosity::Verbose)
    for (size_t p = 0; p < setup.patches.size(); ++p) {
      const PatchNet& n = setup.patches[p];
      std::fprintf(
          stderr,
          "  patch %zu: %zu faces, %zu vertices, %zu loops, %zu free%s, bind net flips %d\n", p,
          n.faces.size(), n.vertices.size(), n.loops.size(), n.free_vertices.size(),
          n.skipped ? " (skipped)" : "", n.bind_net_flips);
    }
  make_output_dir(o.output);

  const size_t count = o.frames.size();
  unsigned threads = o.threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : o.threads;
  threads = static_cast<unsigned>(std::min<size_t>(threads, count));
  cli::Progress progress(count, verbosity, isatty(STDERR_FILENO) != 0);
  std::atomic<size_t> next{0};
  std::atomic<bool> stop{false};
  std::vector<std::unique_ptr<Error>> errors(count);
  auto worker = [&] {
    for (size_t i; !stop && (i = next++) < count;) {
      try {
        progress.done(i, run_frame(setup, bind, o, o.frames[i], outputs[i]));
      } catch (const Error& e) {
        errors[i] = std::make_unique<Error>(e);
        stop = true;  // fail fast: a farm task with a bad frame should fail, not half-succeed
      } catch (const std::exception& e) {
        errors[i] = std::make_unique<Error>(ErrorKind::Internal, o.frames[i] + ": " + e.what());
        stop = true;
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
  progress.finish();
  for (const auto& e : errors)
    if (e) throw *e;  // the first bad frame in list order
  if (verbosity != cli::Verbosity::Quiet)
    std::fprintf(stderr, "skinslide: %zu frames %s in %.2f s -> %s\n", count,
                 o.no_slide ? "copied" : "slid", progress.elapsed_seconds(), o.output.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::setlocale(LC_ALL, "C");
  CliOptions o;
  CLI::App app{"skinslide " + std::string(version()) +
                   ": skin sliding for deformed character meshes (Yang & Zhang 2010, force-density "
                   "bar nets).\n"
                   "Flattens each patch of the bind mesh and of every frame onto the unit square "
                   "and moves the\n"
                   "frame's patch vertices back to where the bind's flattening puts them, on the "
                   "frame's surface.\n"
                   "Patch files list 0-based face ids of the bind (OBJ `f` lines in file order): "
                   "`12`, `12-40`,\n"
                   "`pBody.f[12:40]`; whitespace or commas between them, `#` comments.",
               "skinslide"};
  app.set_version_flag("--version", std::string("skinslide ") + version());
  app.get_formatter()->column_width(36);

  auto* in = "Inputs";
  app.add_option("--patch", o.patches, "Patch file (repeatable; each file's patches are separate)")
      ->required()
      ->allow_extra_args(false)
      ->type_name("FILE")
      ->group(in);
  app.add_option("bind", o.bind, "Bind mesh (.obj)")->required()->type_name("BIND")->group(in);
  app.add_option("frames", o.frames, "Deformed frames: the bind mesh with moved vertices")
      ->required()
      ->type_name("FRAME...")
      ->group(in);

  auto* out = "Output";
  app.add_option("-o,--output", o.output, "Folder for the slid frames (same file names)")
      ->capture_default_str()
      ->type_name("DIR")
      ->group(out);

  auto* method = "Method";
  app.add_option(
         "--density", o.density,
         "Force density q of a bar of length L: paper = 1 - L/Lmax (floored), inverse|length "
         "= Lmin/L, uniform = 1")
      ->capture_default_str()
      ->check(CLI::IsMember({"paper", "inverse", "length", "uniform"}))
      ->group(method);
  app.add_option("--holes", o.holes,
                 "Inner boundary loops in the bind net: free (the paper) or fill (a virtual centre "
                 "node per hole)")
      ->capture_default_str()
      ->check(CLI::IsMember({"free", "fill"}))
      ->group(method);
  app.add_option("--q-floor", o.q_floor, "Smallest force density (paper, inverse)")
      ->capture_default_str()
      ->check(CLI::Range(1e-12, 1.0))
      ->group(method);
  app.add_option(
         "--frame-solver", o.frame_solver,
         "Frame nets: cholesky (sparse, analysis reused by every frame) or cg (warm-started "
         "conjugate gradient; the same nets within --cg-tolerance)")
      ->capture_default_str()
      ->check(CLI::IsMember({"cholesky", "cg"}))
      ->group(method);
  app.add_option("--cg-tolerance", o.cg_tolerance, "Frame net CG stops at |r| <= tol |b|")
      ->capture_default_str()
      ->check(CLI::Range(1e-16, 1e-2))
      ->group(method);
  app.add_option("--cg-max-iterations", o.cg_max_iterations,
                 "Past this the frame net is solved directly (counted)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000))
      ->group(method);
  app.add_option("--locate", o.locate,
                 "Finding bind positions in frame nets: walk (from each vertex's own triangles) or "
                 "image (a triangle-ID image, --lookup-size)")
      ->capture_default_str()
      ->check(CLI::IsMember({"walk", "image"}))
      ->group(method);
  app.add_option("--lookup-size", o.lookup_size, "Side of the triangle-ID lookup image, pixels")
      ->capture_default_str()
      ->check(CLI::Range(8, 16384))
      ->group(method);

  auto* run_group = "Run";
  app.add_option("-j,--threads", o.threads, "Frames processed at once; 0 = all cores")
      ->capture_default_str()
      ->check(CLI::Range(0u, 1024u))
      ->group(run_group);
  app.add_flag("--no-slide", o.no_slide,
               "Read, check and write every frame unchanged, without sliding: the I/O floor of a "
               "run, for timing")
      ->group(run_group);
  app.add_flag("-q,--quiet", o.quiet, "Errors only")->group(run_group);
  app.add_flag("-v,--verbose", o.verbose, "Per-patch detail")->group(run_group);
  app.get_option("--quiet")->excludes("--verbose");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "skinslide: error: %s\nRun with --help for the options.\n", e.what());
    return exit_code(ErrorKind::Usage);
  }
  try {
    return run(o);
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
