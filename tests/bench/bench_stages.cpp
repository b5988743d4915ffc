// Per-stage timings of skinslide's pipeline, calling the library stages directly.
//
//   skinslide_bench_stages [-r REPEAT] [-m paper|elastic] [-s auto|cholesky|multigrid|cg]
//   [-l walk|image] [-b] -o DIR BIND PATCH FRAME...
//       bind read and set-up, then per frame: read (+ topology check); with -m paper (the
//       default here, the stages scripts/bench.sh tabulates) frame net (force densities + solve,
//       with CG iterations), ID image (-l image), locate, transfer; with -m elastic (the
//       command's default method) relax (with its iterations); then write, plus slide_frame as a
//       whole. Prints "name median_ms" lines (medians over frames x repeats). -s and -l are
//       paper options, refused with -m elastic as the command refuses them. -b times the bind
//       read and set-up only (no FRAME needed; the elastic relax of a large patch takes minutes).
//       The I/O floor of a run is the command's own --no-slide.
// Stage times are the thread's CPU time in milliseconds.

#include <algorithm>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "core/allocator.h"
#include "core/error.h"
#include "elastic/relax.h"
#include "io/mesh_formats.h"
#include "io/patch_file.h"
#include "locate/locate.h"
#include "pipeline/bind_setup.h"
#include "pipeline/method.h"
#include "pipeline/options.h"
#include "pipeline/slide_frame.h"
#include "paper/bar_net.h"
#include "paper/force_density.h"
#include "mesh/measures.h"

using namespace skinslide;
namespace fs = std::filesystem;

namespace {

// Stages run on one thread: its CPU time is the stage's time without the waits that other
// processes on a shared machine add to the wall clock.
struct Clock {
  using time_point = double;
  static double now() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
  }
};

double ms_since(double t0) { return Clock::now() - t0; }

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

struct Samples {
  std::map<std::string, std::vector<double>> by_stage;
  void add(const std::string& stage, double value) { by_stage[stage].push_back(value); }
};

// The stages of slide_frame (pipeline/slide_frame.cpp), one patch, each timed on its own.
void time_patch(const BindSetup& setup, size_t index, const Positions3& frame, Samples& s) {
  const Patch& patch = setup.patches[index];
  if (patch.skipped) return;
  auto t0 = Clock::now();
  Positions3 points(patch.vertices.size());
  for (size_t i = 0; i < points.size(); ++i) points[i] = frame[patch.vertices[i]];
  if (const auto* elastic = std::get_if<ElasticMethod>(&setup.method)) {
    // The elastic method: one relaxation in the chart (slide_frame's transfer of its result is
    // the rest of slide_frame's time).
    const ElasticResult relaxed = relax_patch(*elastic->patches[index], points, elastic->options);
    s.add("relax", ms_since(t0));
    s.add("elastic_iterations", relaxed.iterations);
    s.add("elastic_solves", relaxed.solves);
    s.add("elastic_cg_iterations", relaxed.solver_iterations);
    return;
  }
  const PaperOptions& opt = std::get<PaperMethod>(setup.method).options;
  const PaperSetup& paper = std::get<PaperMethod>(setup.method).patches[index];
  const std::vector<double> q =
      force_densities(bar_lengths(points, patch.bars), opt.density, opt.q_floor);
  const FrameNetSolution net = paper.solver->solve(q, frame_net_options(opt));
  s.add("frame_net", ms_since(t0));
  s.add("cg_iterations", net.iterations);
  s.add("direct_solves", net.direct ? 1 : 0);
  Positions2 targets(patch.free_vertices.size());
  for (size_t k = 0; k < targets.size(); ++k) targets[k] = patch.bind_net[patch.free_vertices[k]];
  std::vector<Location> where;
  if (opt.locate == Locate::Image) {
    t0 = Clock::now();
    const IdImage image = id_raster(net.positions, patch.triangles, opt.lookup_size);
    s.add("id_image", ms_since(t0));
    t0 = Clock::now();
    where = locate_points(targets, net.positions, patch.triangles, image);
  } else {
    const std::vector<Index> reversed = count_folds(net.positions, patch.triangles).reversed;
    t0 = Clock::now();
    where = locate_points_by_walk(targets, patch.free_vertices, net.positions, patch.triangles,
                                  paper.topology, reversed);
  }
  s.add("locate", ms_since(t0));
  size_t fallbacks = 0;
  for (const Location& l : where) fallbacks += l.fallback;
  s.add("fallbacks", static_cast<double>(fallbacks));
  t0 = Clock::now();
  Positions3 slid(where.size());
  for (size_t k = 0; k < where.size(); ++k) {
    const Triangle& tri = patch.triangles[where[k].triangle];
    Vec3 p = Vec3::Zero();
    for (int c = 0; c < 3; ++c) p += where[k].weight[c] * points[tri[c]];
    slid[k] = p;
  }
  s.add("transfer", ms_since(t0));
}

int stages(int repeat, const SlideOptions& options, const std::string& out_dir,
           const std::vector<std::string>& args) {
  const std::string& bind_path = args[0];
  const std::string& patch_path = args[1];
  const std::vector<std::string> frames(args.begin() + 2, args.end());
  Samples s;
  auto t0 = Clock::now();
  const MeshFile bind = read_mesh_file(bind_path);
  s.add("bind_read", ms_since(t0));
  const std::vector<std::vector<Index>> selections{
      selected_faces(read_patch(patch_path), bind.mesh.face_count())};
  BindSetup setup;
  for (int r = 0; r < repeat; ++r) {
    t0 = Clock::now();
    setup = bind_setup(bind.mesh, selections, options);
    s.add("bind_setup", ms_since(t0));
  }
  size_t sliding = 0;
  for (const Patch& p : setup.patches) sliding += p.free_vertices.size();
  s.add("patch_vertices", static_cast<double>(sliding));
  s.add("mesh_vertices", bind.mesh.vertex_count());
  if (const auto* elastic = std::get_if<ElasticMethod>(&setup.method)) {
    double factor_entries = 0, factor_mb = 0;
    for (const auto& e : elastic->patches)
      if (e) {
        factor_entries += static_cast<double>(e->metric.factor.entries());
        factor_mb += static_cast<double>(e->metric.factor.bytes()) / 1e6;
      }
    s.add("elastic_factor_entries", factor_entries);
    s.add("elastic_factor_mb", factor_mb);
  }
  fs::create_directories(out_dir);
  for (int r = 0; r < repeat; ++r)
    for (const std::string& path : frames) {
      t0 = Clock::now();
      const MeshFile frame = read_mesh_file(path);
      require_same_topology(bind, frame);
      s.add("read", ms_since(t0));
      for (size_t p = 0; p < setup.patches.size(); ++p)
        time_patch(setup, p, frame.mesh.positions, s);
      t0 = Clock::now();
      const FrameResult result = slide_frame(setup, frame.mesh.positions);
      s.add("slide_frame", ms_since(t0));
      t0 = Clock::now();
      write_slid_mesh_file(frame, result.slid,
                           (fs::path(out_dir) / fs::path(path).filename()).string());
      s.add("write", ms_since(t0));
    }
  for (const auto& [stage, v] : s.by_stage) std::printf("%s %.3f\n", stage.c_str(), median(v));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  restart_with_huge_pages(argv);  // as the command does
  keep_freed_memory();
  try {
    int repeat = 1;
    std::string out_dir;
    SlideOptions options = PaperOptions{};
    bool paper_only = false;
    bool bind_only = false;
    PaperOptions paper;  // -l, -s
    std::vector<std::string> args;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "-r" && i + 1 < argc)
        repeat = std::max(1, std::atoi(argv[++i]));
      else if (a == "-m" && i + 1 < argc)
        options = parse_method(argv[++i]);
      else if (a == "-l" && i + 1 < argc)
        paper.locate = parse_locate(argv[++i]), paper_only = true;
      else if (a == "-s" && i + 1 < argc)
        paper.frame_solver = parse_frame_solver(argv[++i]), paper_only = true;
      else if (a == "-b")
        bind_only = true;
      else if (a == "-o" && i + 1 < argc)
        out_dir = argv[++i];
      else
        args.push_back(a);
    }
    const bool is_paper = std::holds_alternative<PaperOptions>(options);
    if (is_paper) options = paper;
    if (out_dir.empty() || args.size() < (bind_only ? 2u : 3u) || (paper_only && !is_paper)) {
      std::fprintf(stderr,
                   "usage: skinslide_bench_stages [-r REPEAT] [-m paper|elastic] [-s "
                   "auto|cholesky|multigrid|cg] [-l walk|image] [-b] -o DIR BIND PATCH FRAME...\n"
                   "  (-s and -l apply to -m paper only; -b: bind read and set-up only, no "
                   "frames)\n");
      return 2;
    }
    if (bind_only) args.resize(2);
    return stages(repeat, options, out_dir, args);
  } catch (const Error& e) {
    std::fprintf(stderr, "skinslide_bench_stages: error: %s\n", e.what());
    return exit_code(e.kind());
  }
}
