// skinslide: skin sliding after any deformer (Yang & Zhang 2010), a batch command.
// Reads the bind mesh and the patch files once, then slides every frame (in parallel across
// frames only, so the bytes written never depend on the thread count) and writes each slid frame
// as an edited copy of the frame's own file.

#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <chrono>
#include <clocale>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/allocator.h"
#include "core/cores.h"
#include "core/error.h"
#include "core/version.h"
#include "io/atomic_write.h"
#include "io/gltf.h"
#include "io/gltf_weights.h"
#include "io/mesh_file.h"
#include "io/number_format.h"
#include "io/obj_write.h"
#include "io/obj_read.h"
#include "io/patch_file.h"
#include "io/vertex_list.h"
#include "pipeline/bind_setup.h"
#include "pipeline/frame_ranges.h"
#include "pipeline/dumps.h"
#include "pipeline/rig_frames.h"
#include "pipeline/report.h"
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
  std::string mesh;            // glTF: which mesh (name or index); empty = the only one
  bool rig = false;            // --animation given: the frames are BIND posed by its skin
  std::string animation;       // clip name or index
  double fps = 0;              // 0 = the clip's key times
  bool keyframes = false;      // --keyframes: the default, spelled out
  std::string format = "glb";  // of the slid rig frames: obj or glb
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

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// "a,b,c,d" -> four vertex ids.
std::array<Index, 4> parse_corners(const std::string& text) {
  std::array<Index, 4> c{};
  size_t pos = 0;
  for (int j = 0; j < 4; ++j) {
    const size_t comma = j < 3 ? text.find(',', pos) : text.size();
    const auto id = comma == std::string::npos
                        ? std::nullopt
                        : parse_integer(std::string_view(text).substr(pos, comma - pos));
    if (!id || *id < 0 || *id > 2147483647LL || (j < 3 && comma == text.size()))
      throw Error(ErrorKind::Usage, "--corners " + text +
                                        ": expected four vertex ids a,b,c,d (the outer loop's "
                                        "corners in walking order)");
    c[j] = static_cast<Index>(*id);
    pos = comma + 1;
  }
  return c;
}

// The controls read from their files (after the bind: ids are checked against it).
SlideControls slide_controls(const CliOptions& o, const MeshFile& bind, RunReport& report) {
  SlideControls c;
  const Index nv = bind.mesh.vertex_count();
  if (!o.weights.empty()) {
    c.weight = read_weights(o.weights, nv);
    report.weights = o.weights;
  } else if (!o.weights_color.empty()) {
    if (!bind.obj)
      throw Error(ErrorKind::Usage,
                  "--weights-from-obj-color needs an OBJ bind; " + o.bind + " is not one");
    const int channel = o.weights_color == "r" ? 0 : o.weights_color == "g" ? 1 : 2;
    c.weight = obj_color_weights(o.bind, *bind.obj, channel);
    report.weights = o.bind + " (vertex colour " + o.weights_color + ")";
  } else if (!o.weights_attribute.empty()) {
    c.weight = gltf_attribute_weights(bind, o.weights_attribute);
    report.weights = o.bind + " (glTF attribute " + o.weights_attribute + ")";
  }
  c.strength = o.strength;
  report.strength = o.strength;
  if (!o.pin.empty()) {
    c.pins = read_vertex_list(o.pin, nv);
    report.pins = o.pin;
    report.pins_requested = static_cast<Index>(c.pins.size());
  }
  for (const std::string& t : o.corners) c.corners.push_back(parse_corners(t));
  for (int v : o.outer_loop_vertices) c.outer_loop_vertices.push_back(v);
  return c;
}

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
  for (const std::string* f : {&o.weights, &o.pin})
    if (!f->empty()) inputs.push_back(*f);
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
  if (!o.report.empty()) {
    for (const std::string& in : inputs)
      if (same_file(o.report, in))
        throw Error(ErrorKind::Usage, "--report " + o.report + " would overwrite input " + in);
    for (const std::string& f : out)
      if (same_file(o.report, f))
        throw Error(ErrorKind::Usage, "--report " + o.report + " is also the output of a frame");
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

// Indices of the frames that --frames selects, in list order, by the frame number in each
// output's file name (an OBJ frame's own name; a rig frame's <character>.<frame>).
std::vector<size_t> chosen_frames(const std::vector<FrameRange>& ranges,
                                  const std::vector<std::string>& outputs,
                                  const std::vector<std::string>& labels, const std::string& spec) {
  std::vector<size_t> chosen;
  if (ranges.empty()) {
    for (size_t i = 0; i < outputs.size(); ++i) chosen.push_back(i);
    return chosen;
  }
  long long lowest = 0, highest = 0;
  for (size_t i = 0; i < outputs.size(); ++i) {
    const auto n = frame_number(outputs[i]);
    if (!n)
      throw Error(ErrorKind::Usage, "--frames: " + labels[i] +
                                        " has no frame number in its file name (expected e.g. "
                                        "name.0042.obj); drop --frames or rename the frames");
    lowest = i == 0 ? *n : std::min(lowest, *n);
    highest = i == 0 ? *n : std::max(highest, *n);
    // A range past the frames present selects what there is: a farm's last chunk may run past
    // the end of the shot.
    if (in_frame_ranges(ranges, *n)) chosen.push_back(i);
  }
  if (chosen.empty())
    throw Error(ErrorKind::Usage, "--frames " + spec + " selects none of the " +
                                      std::to_string(outputs.size()) + " frames (numbered " +
                                      std::to_string(lowest) + " to " + std::to_string(highest) +
                                      ")");
  return chosen;
}

SlideOptions slide_options(const CliOptions& o) {
  SlideOptions s;
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
  return s;
}

struct FrameSummary {
  int fallbacks = 0;
  double max_slide = 0;
};

FrameSummary summarise(const FrameResult& r) {
  FrameSummary s;
  for (const PatchFrameReport& p : r.patches) {
    s.fallbacks += p.located_fallback;
    s.max_slide = std::max(s.max_slide, p.max_slide);
  }
  return s;
}

std::vector<std::string> frame_report(const BindSetup& setup, const CliOptions& o,
                                      const FrameResult& result, const std::string& frame_path,
                                      const std::string& out_path);

// The report's record of one frame: its figures, not its nets.
void record_frame(ReportFrame& record, const std::string& source, const std::string& out_path,
                  double read_seconds, double write_seconds, const FrameResult& result) {
  record.path = source;
  record.output = out_path;
  record.read_seconds = read_seconds;
  record.write_seconds = write_seconds;
  record.patches = result.patches;
  for (PatchFrameReport& r : record.patches) {
    r.frame_net = {};
    r.id_image = {};
  }
}

// slide_frame, with the frame named in its errors.
FrameResult slide_named(const BindSetup& setup, const CliOptions& o, const Positions3& positions,
                        const std::string& name) {
  try {
    return slide_frame(setup, positions,
                       {.id_image = !o.dump_dir.empty(), .edge_spread = !o.report.empty()});
  } catch (const Error& e) {
    throw Error(e.kind(), name + ": " + e.what());
  }
}

// A frame's dumps and previews, named after `named_after`'s stem. Written before the slid mesh,
// so the slid frame appears only once everything of its frame is written.
void write_frame_pictures(const BindSetup& setup, const CliOptions& o,
                          const std::string& named_after, const Positions3& frame_positions,
                          const FrameResult& result) {
  DumpOptions dump_options;
  dump_options.preview_size = o.preview_size;
  if (!o.dump_dir.empty())
    write_frame_dumps(o.dump_dir, named_after, setup, frame_positions, result.patches,
                      dump_options);
  if (!o.preview_dir.empty())
    write_previews(o.preview_dir, named_after, setup, result.patches, dump_options);
}

// Reads, checks, slides and writes one frame; returns the log lines for it.
std::vector<std::string> run_frame(const BindSetup& setup, const MeshFile& bind,
                                   const CliOptions& o, const std::string& frame_path,
                                   const std::string& out_path, ReportFrame* record) {
  auto t0 = std::chrono::steady_clock::now();
  MeshFile frame = read_mesh_file(frame_path, {o.mesh});
  require_same_topology(bind, frame);
  release_faces(frame);
  const double read_seconds = seconds_since(t0);
  if (o.no_slide) {
    write_slid_mesh_file(frame, SlidVertices{}, out_path);
    return {"skinslide: " + frame_path + ": unchanged (--no-slide) -> " + out_path};
  }
  const FrameResult result = slide_named(setup, o, frame.mesh.positions, frame_path);
  write_frame_pictures(setup, o, frame_path, frame.mesh.positions, result);
  t0 = std::chrono::steady_clock::now();
  write_slid_mesh_file(frame, result.slid, out_path);
  if (record) record_frame(*record, frame_path, out_path, read_seconds, seconds_since(t0), result);
  return frame_report(setup, o, result, frame_path, out_path);
}

// Frame k of a rigged character's clip: posed, slid, written as OBJ or GLB.
std::vector<std::string> run_rig_frame(const BindSetup& setup, const MeshFile& character,
                                       const RigClip& clip, const CliOptions& o, size_t k,
                                       const std::string& out_path, ReportFrame* record) {
  const std::string label = clip.names[k] + " (t = " + fmt(clip.times[k]) + " s)";
  auto t0 = std::chrono::steady_clock::now();
  const MeshFile frame = rig_frame(character, clip, k);
  const double pose_seconds = seconds_since(t0);
  const FrameResult result = slide_named(setup, o, frame.mesh.positions, label);
  write_frame_pictures(setup, o, out_path, frame.mesh.positions, result);
  t0 = std::chrono::steady_clock::now();
  if (o.format == "obj")
    write_file_atomic(out_path, obj_text(frame.mesh, apply_slide(frame.mesh.positions, result.slid),
                                         character.path + ", " + label + ", slid"));
  else
    write_gltf_file(frame, result.slid, out_path);
  if (record) record_frame(*record, label, out_path, pose_seconds, seconds_since(t0), result);
  return frame_report(setup, o, result, label, out_path);
}

std::string solver_label(FrameNetMethod method, int iterations) {
  switch (method) {
    case FrameNetMethod::Cholesky:
      return "Cholesky";
    case FrameNetMethod::Cg:
      return "CG " + std::to_string(iterations) + " it";
    case FrameNetMethod::Multigrid:
      return "multigrid " + std::to_string(iterations) + " it";
  }
  return "?";
}

// The frame's solvers, each once, in patch order; an iterative one with its most iterations.
std::string solvers_used(const BindSetup& setup, const FrameResult& result) {
  std::vector<std::pair<FrameNetMethod, int>> used;
  for (size_t p = 0; p < result.patches.size(); ++p) {
    if (setup.patches[p].skipped) continue;
    const FrameNetMethod m = setup.patches[p].solver->method();
    auto it = std::find_if(used.begin(), used.end(), [&](const auto& u) { return u.first == m; });
    if (it == used.end()) it = used.insert(used.end(), {m, 0});
    it->second = std::max(it->second, result.patches[p].cg_iterations);
  }
  if (used.empty()) return "no frame net";
  std::string text;
  for (const auto& [method, iterations] : used)
    text += (text.empty() ? "" : " + ") + solver_label(method, iterations);
  return text;
}

// One patch of an elastic frame, for -v.
std::string elastic_patch_line(const PatchFrameReport& r) {
  return "elastic " + std::to_string(r.iterations) + " it (" + r.stop + "), energy " +
         fmt(r.energy_before) + " -> " + fmt(r.energy_after) + ", held " +
         std::to_string(r.held) + ", flips " + std::to_string(r.slid_flips) + ", slide max " +
         fmt(r.max_slide) + " mean " + fmt(r.mean_slide);
}

// The elastic frame's summary: most steps, and the energy left as a share of the frame's.
std::string elastic_summary(const BindSetup& setup, const FrameResult& result) {
  int iterations = 0, flips = 0;
  double before = 0, after = 0;
  for (size_t p = 0; p < result.patches.size(); ++p) {
    if (setup.patches[p].skipped) continue;
    const PatchFrameReport& r = result.patches[p];
    iterations = std::max(iterations, r.iterations);
    flips += r.slid_flips;
    before += r.energy_before;
    after += r.energy_after;
  }
  return "elastic " + std::to_string(iterations) + " it, energy left " +
         (before > 0 ? fmt(100 * after / before) + "%" : std::string("0")) + ", flips " +
         std::to_string(flips);
}

std::vector<std::string> frame_report(const BindSetup& setup, const CliOptions& o,
                                      const FrameResult& result, const std::string& frame_path,
                                      const std::string& out_path) {
  const FrameSummary s = summarise(result);
  const bool elastic = setup.options.method == SlideMethod::Elastic;
  std::vector<std::string> lines;
  lines.push_back("skinslide: " + frame_path + ": " + std::to_string(setup.patches.size()) +
                  " patches, " +
                  (elastic ? elastic_summary(setup, result) : solvers_used(setup, result)) +
                  ", max slide " + fmt(s.max_slide) +
                  (elastic ? std::string() : ", " + std::to_string(s.fallbacks) + " fallbacks") +
                  " -> " + out_path);
  if (o.verbose)
    for (size_t p = 0; p < result.patches.size(); ++p) {
      const PatchFrameReport& r = result.patches[p];
      const PatchNet& n = setup.patches[p];
      std::string line;
      if (n.skipped)
        line = "skipped (all vertices on loops)";
      else if (elastic)
        line = elastic_patch_line(r);
      else
        line = solver_label(n.solver->method(), r.cg_iterations) +
               (n.solver->method() == FrameNetMethod::Cholesky
                    ? ""
                    : ", residual " + fmt(r.cg_residual)) +
               (r.direct_solve ? " (solved directly)" : "") + ", located " +
               std::to_string(r.located_in_image) + " + " + std::to_string(r.located_fallback) +
               " fallback, net flips " + std::to_string(r.frame_net_flips) + ", slide max " +
               fmt(r.max_slide) + " mean " + fmt(r.mean_slide);
      lines.push_back("  patch " + std::to_string(p) + ": " + line);
    }
  return lines;
}

int run(const CliOptions& o) {
  const cli::Verbosity verbosity =
      o.quiet ? cli::Verbosity::Quiet
              : (o.verbose ? cli::Verbosity::Verbose : cli::Verbosity::Normal);
  const auto t_run = std::chrono::steady_clock::now();
  const SlideOptions options = slide_options(o);
  const std::vector<FrameRange> ranges =
      o.frame_ranges.empty() ? std::vector<FrameRange>{} : parse_frame_ranges(o.frame_ranges);
  std::vector<std::string> outputs = o.rig ? std::vector<std::string>{} : output_paths(o);
  std::vector<size_t> chosen;
  if (!o.rig) chosen = chosen_frames(ranges, outputs, o.frames, o.frame_ranges);
  if (!o.rig && (!o.dump_dir.empty() || !o.preview_dir.empty())) check_dump_stems(o.frames);

  // With --animation, BIND is a rigged glTF character: the bind is its mesh as stored, the
  // frames its skin posed at the clip's sampled times (pipeline/rig_frames.h).
  MeshFile bind = o.rig ? read_gltf_file(o.bind, {o.mesh}) : read_mesh_file(o.bind, {o.mesh});
  RigClip clip;
  if (o.rig) {
    clip = rig_clip(bind, {o.animation, o.fps});
    std::vector<std::string> inputs = o.patches;
    inputs.push_back(o.bind);
    for (const std::string& name : clip.names) {
      const fs::path target = fs::path(o.output) / (name + "." + o.format);
      for (const std::string& in : inputs)
        if (same_file(target, in))
          throw Error(ErrorKind::Usage, "output " + target.string() + " would overwrite input " +
                                            in + "; choose another --output folder");
      outputs.push_back(target.string());
    }
    chosen = chosen_frames(ranges, outputs, clip.names, o.frame_ranges);
  }
  std::vector<std::vector<Index>> selections;
  for (const std::string& p : o.patches)
    selections.push_back(selected_faces(read_patch(p), bind.mesh.face_count()));
  RunReport report;
  const SlideControls controls = slide_controls(o, bind, report);
  // The bind file's contents served the controls (vertex colours, attributes); from here on the
  // frames need only its mesh, unless it is the character the frames are posed from. At 1M
  // vertices an OBJ's text and token spans are about 70 MB held for the whole run.
  if (!o.rig) {
    bind.obj.reset();
    bind.gltf.reset();
  }
  unsigned threads = o.threads == 0 ? usable_cores() : o.threads;
  // --no-slide measures the I/O floor of a run: no bind set-up, frames copied unchanged.
  const BindSetup setup =
      o.no_slide ? BindSetup{}
                 : bind_setup(
                       bind.mesh, selections, options, controls,
                       [&](Index f) {
                         return "face " + std::to_string(f) + " (" + bind.where_face(f) + ")";
                       },
                       threads);
  report.bind_seconds = seconds_since(t_run);
  size_t sliding = 0;
  for (const PatchNet& p : setup.patches) sliding += p.free_vertices.size();
  if (o.no_slide && verbosity != cli::Verbosity::Quiet)
    std::fprintf(stderr,
                 "skinslide: %s: --no-slide: frames are read, checked and written unchanged\n",
                 o.bind.c_str());
  else if (verbosity != cli::Verbosity::Quiet)
    std::fprintf(stderr,
                 "skinslide: %s: %zu patches, %zu sliding vertices (%s)\n", o.bind.c_str(),
                 setup.patches.size(), sliding,
                 options.method == SlideMethod::Paper
                     ? ("method paper, density " + to_string(options.density) + ", holes " +
                        to_string(options.holes))
                           .c_str()
                     : "method elastic");
  if (verbosity == cli::Verbosity::Verbose)
    for (size_t p = 0; p < setup.patches.size(); ++p) {
      const PatchNet& n = setup.patches[p];
      std::fprintf(
          stderr,
          "  patch %zu: %zu faces, %zu vertices, %zu loops, %zu free%s, bind net flips %d\n", p,
          n.faces.size(), n.vertices.size(), n.loops.size(), n.free_vertices.size(),
          n.skipped ? " (skipped)" : "", n.bind_net_flips);
      if (!n.skipped && n.elastic)  // the elastic chart is a disk: no corners
        std::fprintf(stderr, "    outer loop from vertex %d%s, %zu pinned\n",
                     n.vertices[n.loops[n.outer_loop].front()],
                     n.outer_loop_chosen ? " (chosen)" : "", n.pinned.size());
      else if (!n.skipped)
        std::fprintf(stderr, "    outer loop from vertex %d%s, corners %d,%d,%d,%d%s, %zu pinned\n",
                     n.vertices[n.loops[n.outer_loop].front()],
                     n.outer_loop_chosen ? " (chosen)" : "", n.vertices[n.corners[0]],
                     n.vertices[n.corners[1]], n.vertices[n.corners[2]], n.vertices[n.corners[3]],
                     n.corners_chosen ? " (chosen)" : "", n.pinned.size());
    }
  if (verbosity == cli::Verbosity::Verbose && !controls.pins.empty())
    std::fprintf(stderr,
                 "  %zu pins, %d of them on a boundary loop or outside every patch (ignored)\n",
                 controls.pins.size(), setup.pins_ignored);
  make_output_dir(o.output);
  if (!o.dump_dir.empty()) write_bind_dumps(o.dump_dir, o.bind, setup, bind.mesh.positions);

  const size_t count = chosen.size();
  threads = static_cast<unsigned>(std::min<size_t>(threads, count));
  if (verbosity == cli::Verbosity::Verbose)
    std::fprintf(stderr, "  %zu frames, %u at a time%s\n", count, threads,
                 o.threads == 0 ? " (-j 0: the cores this task may use)" : "");
  cli::Progress progress(count, verbosity, isatty(STDERR_FILENO) != 0);
  std::atomic<size_t> next{0};
  std::atomic<bool> stop{false};
  std::vector<std::unique_ptr<Error>> errors(count);
  if (!o.report.empty()) report.frames.resize(count);
  auto worker = [&] {
    for (size_t j; !stop && (j = next++) < count;) {
      const size_t i = chosen[j];
      try {
        ReportFrame* record = o.report.empty() ? nullptr : &report.frames[j];
        progress.done(j, o.rig ? run_rig_frame(setup, bind, clip, o, i, outputs[i], record)
                               : run_frame(setup, bind, o, o.frames[i], outputs[i], record));
        continue;
      } catch (const Error& e) {
        errors[j] = std::make_unique<Error>(e);
      } catch (const std::bad_alloc&) {
        errors[j] = std::make_unique<Error>(
            ErrorKind::Internal, (o.rig ? clip.names[i] : o.frames[i]) + ": out of memory");
      } catch (const std::exception& e) {
        errors[j] = std::make_unique<Error>(
            ErrorKind::Internal, (o.rig ? clip.names[i] : o.frames[i]) + ": " + e.what());
      }
      // Fail fast by default: a farm task with a bad frame should fail, not half-succeed
      // (README "Exit codes"). --keep-going writes every good frame and names every bad one.
      if (o.keep_going)
        progress.done(j, {});
      else
        stop = true;
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
  progress.finish();
  // Each output was flushed before its rename; flushing the folders makes the renames durable.
  for (const std::string& folder : {o.output, o.dump_dir, o.preview_dir})
    if (!folder.empty()) sync_folder(folder);
  size_t failed = 0;
  const Error* first = nullptr;
  for (const auto& e : errors)
    if (e) {
      ++failed;
      if (!first) first = e.get();  // the first bad frame in list order decides the exit code
    }
  if (first && !o.keep_going) throw *first;
  for (const auto& e : errors)
    if (e) std::fprintf(stderr, "skinslide: error: %s\n", e->what());
  if (!o.report.empty()) {
    report.bind = o.bind;
    report.patch_files = o.patches;
    report.timings = !o.report_no_timings;
    report.wall_seconds = seconds_since(t_run);
    // --keep-going: the report lists the frames written.
    std::erase_if(report.frames, [](const ReportFrame& r) { return r.output.empty(); });
    write_file_atomic(o.report, report_json(setup, report));
    const fs::path report_folder = fs::path(o.report).parent_path();
    sync_folder(report_folder.empty() ? "." : report_folder.string());
  }
  if (verbosity != cli::Verbosity::Quiet || failed > 0)
    std::fprintf(stderr, "skinslide: %zu frames %s%s in %.2f s -> %s\n", count - failed,
                 o.no_slide ? "copied" : "slid",
                 failed ? (", " + std::to_string(failed) + " failed").c_str() : "",
                 progress.elapsed_seconds(), o.output.c_str());
  if (first) return exit_code(first->kind());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  skinslide::restart_with_huge_pages(argv);
  std::setlocale(LC_ALL, "C");
  skinslide::keep_freed_memory();
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
          "  skinslide --patch P.txt --animation NAME|INDEX [--fps N | --keyframes] character.glb",
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
                     "Deformed frames: the bind mesh with moved vertices (none with --animation)")
          ->type_name("FRAME...")
          ->group(in);

  auto* gl = "glTF";
  app.add_option("--mesh", o.mesh, "Mesh of a .gltf/.glb holding several (name, else index)")
      ->type_name("NAME|INDEX")
      ->group(gl);
  auto* anim = app.add_option("--animation", o.animation,
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
  app.add_option("--format", o.format,
                 "Format of the slid frames of --animation, named <character>.<frame>.<format>, "
                 "frame numbers from 0000")
      ->capture_default_str()
      ->check(CLI::IsMember({"obj", "glb"}))
      ->needs(anim)
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
                 "Elastic: a round stops once two steps in a row each lower its energy by less "
                 "than this fraction of its starting energy")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0))
      ->group(method);
  app.add_option(
         "--density", o.density,
         "Paper: force density q of a bar of length L: paper = 1 - L/Lmax (floored), inverse|length "
         "= Lmin/L, uniform = 1")
      ->capture_default_str()
      ->check(CLI::IsMember({"paper", "inverse", "length", "uniform"}))
      ->group(method);
  app.add_option("--holes", o.holes,
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
      "Paper: how bind and frame nets are solved: cholesky (sparse factor, analysis reused by every "
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
  app.add_option("--cg-tolerance", o.cg_tolerance,
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
  app.add_option("--locate", o.locate,
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
    std::string ext = fs::path(o.bind).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    const bool gltf_bind = ext == ".gltf" || ext == ".glb";
    if (o.rig && !gltf_bind)
      throw CLI::ValidationError("--animation", "needs a .gltf or .glb BIND, not " + o.bind);
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
