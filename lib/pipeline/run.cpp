#include "pipeline/run.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <new>
#include <set>
#include <string_view>
#include <thread>
#include <utility>

#include "core/cores.h"
#include "io/atomic_write.h"
#include "io/gltf.h"
#include "io/gltf_weights.h"
#include "io/mesh_file.h"
#include "io/number_format.h"
#include "io/obj_write.h"
#include "io/obj_rewrite.h"
#include "io/patch_file.h"
#include "io/point_cache.h"
#include "io/vertex_list.h"
#include "pipeline/bind_setup.h"
#include "pipeline/cache_frames.h"
#include "pipeline/dumps.h"
#include "pipeline/frame_ranges.h"
#include "pipeline/report.h"
#include "pipeline/slide_frame.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Same file (by identity when it exists, else by normalised path).
bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

// Every file a run reads: no output may be one of them.
std::vector<std::string> run_inputs(const RunOptions& o) {
  std::vector<std::string> inputs = o.frames;
  inputs.push_back(o.bind);
  inputs.insert(inputs.end(), o.patches.begin(), o.patches.end());
  for (const std::string* f : {&o.weights, &o.pin})
    if (!f->empty()) inputs.push_back(*f);
  return inputs;
}

void refuse_overwrite(const std::string& target, const std::vector<std::string>& inputs) {
  for (const std::string& in : inputs)
    if (same_file(target, in))
      throw Error(ErrorKind::Usage, "output " + target + " would overwrite input " + in +
                                        "; choose another --output folder");
}

// A cache output and, for a chunk, the shot's cache its join makes in that folder
// (`skinslide join`): neither may be an input, or the join would replace the shot it came from.
void refuse_cache_overwrite(const std::string& cache, const std::string& joined,
                            const std::vector<std::string>& inputs) {
  refuse_overwrite(cache, inputs);
  for (const std::string& in : inputs)
    if (cache != joined && same_file(joined, in))
      throw Error(ErrorKind::Usage, "output " + cache + ": its chunks would join into " + joined +
                                        ", which is input " + in +
                                        "; choose another --output folder");
}

// The report must overwrite neither an input nor an output.
void refuse_report_overwrite(const RunOptions& o, const std::vector<std::string>& inputs,
                             const std::vector<std::string>& outputs) {
  if (o.report.empty()) return;
  for (const std::string& in : inputs)
    if (same_file(o.report, in))
      throw Error(ErrorKind::Usage, "--report " + o.report + " would overwrite input " + in);
  for (const std::string& f : outputs)
    if (same_file(o.report, f))
      throw Error(ErrorKind::Usage, "--report " + o.report + " is also the output of a frame");
}

std::vector<FrameRange> frame_ranges(const RunOptions& o) {
  return o.frame_ranges.empty() ? std::vector<FrameRange>{} : parse_frame_ranges(o.frame_ranges);
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

void make_output_dir(const std::string& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw Error(ErrorKind::Output, dir + ": cannot write: exists and is not a folder");
  fs::create_directories(dir, ec);
  if (ec)
    throw Error(ErrorKind::Output, dir + ": cannot create the output folder: " + ec.message());
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
SlideControls slide_controls(const RunOptions& o, const MeshFile& bind, RunReport& report) {
  SlideControls c;
  const Index nv = bind.mesh.vertex_count();
  if (!o.weights.empty()) {
    c.weight = read_weights(o.weights, nv);
    report.weights = o.weights;
  } else if (!o.weights_from_obj_color.empty()) {
    if (!bind.obj)
      throw Error(ErrorKind::Usage,
                  "--weights-from-obj-color needs an OBJ bind; " + o.bind + " is not one");
    const std::string& color = o.weights_from_obj_color;
    const int channel = color == "r" ? 0 : color == "g" ? 1 : 2;
    c.weight = obj_color_weights(o.bind, *bind.obj, channel);
    report.weights = o.bind + " (vertex colour " + color + ")";
  } else if (!o.weights_from_gltf_attribute.empty()) {
    c.weight = gltf_attribute_weights(bind, o.weights_from_gltf_attribute);
    report.weights = o.bind + " (glTF attribute " + o.weights_from_gltf_attribute + ")";
  }
  c.strength = o.strength;
  report.strength = o.strength;
  if (!o.pin.empty()) {
    c.pins = read_vertex_list(o.pin, nv);
    report.pins = o.pin;
    report.pins_requested = static_cast<Index>(c.pins.size());
  }
  for (const std::string& t : o.corners) c.corners.push_back(parse_corners(t));
  for (Index v : o.outer_loop_vertices) c.outer_loop_vertices.push_back(v);
  return c;
}

// ---- A frame's log lines ----------------------------------------------------------------------

// A slid frame's lines: a summary (Info), then a line per patch (Detail).
std::vector<LogLine> frame_lines(const BindSetup& setup, const FrameResult& result,
                                 const std::string& frame_path, const std::string& out_path) {
  double max_slide = 0;
  for (const PatchFrameReport& p : result.patches) max_slide = std::max(max_slide, p.max_slide);
  const std::vector<MethodReport> reports = method_reports(result.patches);
  std::vector<LogLine> lines;
  lines.push_back({LogLevel::Info, "skinslide: " + frame_path + ": " +
                                       std::to_string(setup.patches.size()) + " patches, " +
                                       frame_summary(setup.method, setup.patches, reports,
                                                     ", max slide " + log_number(max_slide)) +
                                       " -> " + out_path});
  for (size_t p = 0; p < result.patches.size(); ++p) {
    const PatchFrameReport& r = result.patches[p];
    const std::string line = setup.patches[p].skipped
                                 ? "skipped (all vertices on loops)"
                                 : patch_summary(setup.method, p, r.method) + ", slide max " +
                                       log_number(r.max_slide) + " mean " +
                                       log_number(r.mean_slide);
    lines.push_back({LogLevel::Detail, "  patch " + std::to_string(p) + ": " + line});
  }
  return lines;
}

// The bind's lines: a summary (Info), then per patch its nets and loops (Detail).
std::vector<LogLine> bind_lines(const RunOptions& o, const BindSetup& setup,
                                const SlideControls& controls) {
  std::vector<LogLine> lines;
  size_t sliding = 0;
  for (const Patch& p : setup.patches) sliding += p.free_vertices.size();
  if (o.no_slide)
    lines.push_back({LogLevel::Info, "skinslide: " + o.bind +
                                         ": --no-slide: frames are read, checked and written "
                                         "unchanged"});
  else
    lines.push_back({LogLevel::Info, "skinslide: " + o.bind + ": " +
                                         std::to_string(setup.patches.size()) + " patches, " +
                                         std::to_string(sliding) + " sliding vertices (" +
                                         method_label(setup.method) + ")"});
  const auto v = [&](const Patch& n, Index local) { return std::to_string(n.vertices[local]); };
  for (size_t p = 0; p < setup.patches.size(); ++p) {
    const Patch& n = setup.patches[p];
    lines.push_back({LogLevel::Detail, "  patch " + std::to_string(p) + ": " +
                                           std::to_string(n.faces.size()) + " faces, " +
                                           std::to_string(n.vertices.size()) + " vertices, " +
                                           std::to_string(n.loops.size()) + " loops, " +
                                           std::to_string(n.free_vertices.size()) + " free" +
                                           (n.skipped ? " (skipped)" : "") + ", bind net flips " +
                                           std::to_string(n.bind_net_flips)});
    if (n.skipped) continue;
    std::string loop = "    outer loop from vertex " + v(n, n.loops[n.outer_loop].front()) +
                       (n.outer_loop_chosen ? " (chosen)" : "");
    if (const auto c = square_corners(setup.method, p, n))  // the elastic chart is a disk: none
      loop += ", corners " + std::to_string(c->vertices[0]) + "," + std::to_string(c->vertices[1]) +
              "," + std::to_string(c->vertices[2]) + "," + std::to_string(c->vertices[3]) +
              (c->chosen ? " (chosen)" : "");
    lines.push_back({LogLevel::Detail, loop + ", " + std::to_string(n.pinned.size()) + " pinned"});
  }
  if (!controls.pins.empty())
    lines.push_back({LogLevel::Detail, "  " + std::to_string(controls.pins.size()) + " pins, " +
                                           std::to_string(setup.pins_ignored) +
                                           " of them on a boundary loop or outside every patch "
                                           "(ignored)"});
  return lines;
}

// ---- One frame -------------------------------------------------------------------------------

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
FrameResult slide_named(const BindSetup& setup, const RunOptions& o, const Positions3& positions,
                        const std::string& name) {
  try {
    return slide_frame(setup, positions,
                       {.id_image_size = o.dump_dir.empty() ? 0 : o.lookup_size,
                        .edge_spread = !o.report.empty()});
  } catch (const Error& e) {
    throw Error(e.kind(), name + ": " + e.what());
  }
}

// A frame's dumps and previews, named after `named_after`'s stem. Written before the slid mesh,
// so the slid frame appears only once everything of its frame is written.
void write_frame_pictures(const BindSetup& setup, const RunOptions& o,
                          const std::string& named_after, const Positions3& frame_positions,
                          const FrameResult& result) {
  DumpOptions dump_options;
  dump_options.id_image_size = o.lookup_size;
  dump_options.preview_size = o.preview_size;
  if (!o.dump_dir.empty())
    write_frame_dumps(o.dump_dir, named_after, setup, frame_positions, result.patches,
                      dump_options);
  if (!o.preview_dir.empty())
    write_previews(o.preview_dir, named_after, setup, result.patches, dump_options);
}

// Reads, checks, slides and writes one frame; returns the log lines for it.
std::vector<LogLine> run_frame(const BindSetup& setup, const MeshFile& bind, const RunOptions& o,
                               const std::string& frame_path, const std::string& out_path,
                               ReportFrame* record) {
  auto t0 = std::chrono::steady_clock::now();
  MeshFile frame = read_mesh_file(frame_path, {o.mesh});
  require_same_topology(bind, frame);
  release_faces(frame);
  const double read_seconds = seconds_since(t0);
  if (o.no_slide) {
    write_slid_mesh_file(frame, SlidVertices{}, out_path);
    return {
        {LogLevel::Info, "skinslide: " + frame_path + ": unchanged (--no-slide) -> " + out_path}};
  }
  const FrameResult result = slide_named(setup, o, frame.mesh.positions, frame_path);
  write_frame_pictures(setup, o, frame_path, frame.mesh.positions, result);
  t0 = std::chrono::steady_clock::now();
  write_slid_mesh_file(frame, result.slid, out_path);
  if (record) record_frame(*record, frame_path, out_path, read_seconds, seconds_since(t0), result);
  return frame_lines(setup, result, frame_path, out_path);
}

// Where a frame goes in the point cache a run writes (FramePlan::cache): the cache's writer and
// the frame's sample in it. No writer: the frame has a file of its own.
struct CacheSlot {
  CacheWriter* writer = nullptr;
  size_t sample = 0;
};

// A frame read from a point cache (its coordinates `frame`, as `positions`), slid by `slid`,
// written where the plan says: a sample of the output cache (unslid coordinates copied bit for
// bit), or a file of its own: the OBJ bind's own text with the frame's positions, a welded OBJ
// of a glTF bind, or a static copy of the glTF bind.
void write_cache_frame(const MeshFile& bind, const RunOptions& o, CacheSample frame,
                       const Positions3& positions, const SlidVertices& slid,
                       const std::string& out_path, CacheSlot slot, const std::string& label) {
  if (slot.writer)
    return slot.writer->write_sample(slot.sample, slid_sample(std::move(frame), slid));
  if (o.format == "glb") return write_gltf_file(gltf_at_positions(bind, positions), slid, out_path);
  const Positions3 slid_positions = apply_slide(positions, slid);
  if (bind.obj)
    return write_rewritten_obj(out_path, *bind.obj, bind.mesh.positions, slid_positions);
  write_file_atomic(out_path, obj_text(bind.mesh, slid_positions, label + ", slid"));
}

// Sample k of a point cache: read, slid and written (write_cache_frame).
std::vector<LogLine> run_cache_frame(const BindSetup& setup, const MeshFile& bind,
                                     const CacheFrames& cache, const RunOptions& o, size_t k,
                                     const std::string& out_path, CacheSlot slot,
                                     ReportFrame* record) {
  const std::string label =
      cache.cache->path() + " sample " + std::to_string(k) + " (" + cache.names[k] + ")";
  auto t0 = std::chrono::steady_clock::now();
  CacheSample frame = cache.cache->sample(k);
  const Positions3 positions = sample_positions(frame);
  const double read_seconds = seconds_since(t0);
  FrameResult result;
  if (!o.no_slide) {
    result = slide_named(setup, o, positions, label);
    write_frame_pictures(setup, o, cache.names[k] + ".cache", positions, result);
  }
  t0 = std::chrono::steady_clock::now();
  write_cache_frame(bind, o, std::move(frame), positions, result.slid, out_path, slot, label);
  if (o.no_slide)
    return {{LogLevel::Info, "skinslide: " + label + ": unchanged (--no-slide) -> " + out_path}};
  if (record) record_frame(*record, label, out_path, read_seconds, seconds_since(t0), result);
  return frame_lines(setup, result, label, out_path);
}

// The header of the cache a run writes: the chosen samples of the FRAME cache, or of the clip.
CacheHeader output_cache_header(const RunOptions& o, const FramePlan& plan, const MeshFile& bind,
                                const RigClip& clip, const CacheFrames& cache) {
  const CacheHeader whole =
      cache.cache ? cache.cache->header()
                  : rig_cache_header(o.format == "pc2" ? CacheFormat::Pc2 : CacheFormat::Mdd,
                                     bind.mesh.vertex_count(), clip.times);
  return cache_output_header(whole, plan.chosen);
}

// Frame k of a rigged character's clip: posed, slid, written as OBJ or GLB, or into a cache.
std::vector<LogLine> run_rig_frame(const BindSetup& setup, const MeshFile& character,
                                   const RigClip& clip, const RunOptions& o, size_t k,
                                   const std::string& out_path, CacheSlot slot,
                                   ReportFrame* record) {
  const std::string label = clip.names[k] + " (t = " + log_number(clip.times[k]) + " s)";
  auto t0 = std::chrono::steady_clock::now();
  const MeshFile frame = rig_frame(character, clip, k);
  const double pose_seconds = seconds_since(t0);
  const FrameResult result = slide_named(setup, o, frame.mesh.positions, label);
  write_frame_pictures(setup, o, out_path, frame.mesh.positions, result);
  t0 = std::chrono::steady_clock::now();
  if (slot.writer)
    slot.writer->write_sample(slot.sample,
                              positions_sample(apply_slide(frame.mesh.positions, result.slid)));
  else if (o.format == "obj")
    write_file_atomic(out_path, obj_text(frame.mesh, apply_slide(frame.mesh.positions, result.slid),
                                         character.path + ", " + label + ", slid"));
  else
    write_gltf_file(frame, result.slid, out_path);
  if (record) record_frame(*record, label, out_path, pose_seconds, seconds_since(t0), result);
  return frame_lines(setup, result, label, out_path);
}

// A run's frames besides FRAME files: a rigged character's clip or a point cache's samples; and
// where every frame goes.
struct FrameSource {
  FramePlan plan;
  RigClip clip;       // --animation
  CacheFrames cache;  // a point cache FRAME
};

// The plan of FRAME files is made before the bind is read; a clip's and a cache's once the
// character or the cache's header is: with --animation, BIND is a rigged glTF character whose
// frames are its skin posed at the clip's sampled times (pipeline/rig_frames.h); a cache's
// frames are its samples (pipeline/cache_frames.h).
FrameSource frame_source(const RunOptions& o, const MeshFile& bind, FramePlan files,
                         bool cache_run) {
  FrameSource source;
  source.plan = std::move(files);
  if (o.rig) {
    source.clip = rig_clip(bind, *o.rig);
    source.plan = plan_rig_frames(o, source.clip.names);
  }
  if (cache_run) {
    source.cache = open_cache_frames(o.frames.front(), bind);
    source.plan = plan_cache_frames(o, source.cache.cache->header(), source.cache.names);
    std::vector<std::string> dump_names;
    for (size_t k : source.plan.chosen) dump_names.push_back(source.cache.names[k] + ".cache");
    if (!o.dump_dir.empty() || !o.preview_dir.empty()) check_dump_stems(dump_names);
  }
  return source;
}

// Frame i of the run, for its errors.
const std::string& frame_label(const RunOptions& o, const FrameSource& source, size_t i) {
  if (o.rig) return source.clip.names[i];
  return source.cache.cache ? source.cache.names[i] : o.frames[i];
}

// Frame i of the run: read (or posed), slid and written; its log lines.
std::vector<LogLine> run_source_frame(const BindSetup& setup, const MeshFile& bind,
                                      const FrameSource& source, const RunOptions& o, size_t i,
                                      CacheSlot slot, ReportFrame* record) {
  const std::string& out = source.plan.outputs[i];
  if (o.rig) return run_rig_frame(setup, bind, source.clip, o, i, out, slot, record);
  if (source.cache.cache)
    return run_cache_frame(setup, bind, source.cache, o, i, out, slot, record);
  return run_frame(setup, bind, o, o.frames[i], out, record);
}

}  // namespace

FramePlan plan_frames(const RunOptions& o) {
  const std::vector<FrameRange> ranges = frame_ranges(o);
  const std::vector<std::string> inputs = run_inputs(o);
  FramePlan plan;
  std::set<std::string> names;
  for (const std::string& f : o.frames) {
    const std::string name = fs::path(f).filename().string();
    if (!names.insert(name).second)
      throw Error(ErrorKind::Usage, "two frames are named '" + name + "'; their outputs in " +
                                        o.output + " would collide");
    const std::string target = (fs::path(o.output) / name).string();
    refuse_overwrite(target, inputs);
    plan.outputs.push_back(target);
  }
  refuse_report_overwrite(o, inputs, plan.outputs);
  plan.chosen = chosen_frames(ranges, plan.outputs, o.frames, o.frame_ranges);
  return plan;
}

FramePlan plan_rig_frames(const RunOptions& o, const std::vector<std::string>& names) {
  const std::vector<FrameRange> ranges = frame_ranges(o);
  std::vector<std::string> inputs = o.patches;
  inputs.push_back(o.bind);
  const std::string format = o.format.empty() ? "glb" : o.format;
  FramePlan plan;
  for (const std::string& name : names) {
    const std::string target = (fs::path(o.output) / (name + "." + format)).string();
    refuse_overwrite(target, inputs);
    plan.outputs.push_back(target);
  }
  plan.chosen = chosen_frames(ranges, plan.outputs, names, o.frame_ranges);
  if (is_cache_format(format)) {
    // The clip's frames as samples of one cache: frame numbers are the sample indices.
    CacheHeader whole;
    whole.format = format == "pc2" ? CacheFormat::Pc2 : CacheFormat::Mdd;
    whole.samples = static_cast<std::int32_t>(names.size());
    const std::string stem = fs::path(o.bind).stem().string();
    plan.cache = cache_output_path(o.output, stem, "." + format, whole, plan.chosen);
    refuse_cache_overwrite(plan.cache, (fs::path(o.output) / (stem + "." + format)).string(),
                           inputs);
    plan.outputs.assign(names.size(), plan.cache);
  }
  return plan;
}

FramePlan plan_cache_frames(const RunOptions& o, const CacheHeader& cache,
                            const std::vector<std::string>& names) {
  const std::vector<std::string> inputs = run_inputs(o);
  const std::string own = to_string(cache.format);
  const std::string format = o.format.empty() ? own : o.format;
  FramePlan plan;
  plan.chosen = chosen_samples(cache, o.frame_ranges);
  if (is_cache_format(format)) {
    if (format != own)
      throw Error(ErrorKind::Usage, "--format " + format + ": " + o.frames.front() + " is a " +
                                        own +
                                        " cache; a cache is written in its own format "
                                        "(PC2 frames and MDD times do not convert without a "
                                        "frame rate)");
    const fs::path input(o.frames.front());
    plan.cache = cache_output_path(o.output, input.stem().string(), input.extension().string(),
                                   cache, plan.chosen);
    refuse_cache_overwrite(plan.cache, (fs::path(o.output) / input.filename()).string(), inputs);
    plan.outputs.assign(names.size(), plan.cache);
  } else {
    plan.outputs.resize(names.size());
    std::set<std::string> taken;
    for (std::size_t k : plan.chosen) {
      if (!taken.insert(names[k]).second)
        throw Error(ErrorKind::Usage, "--format " + format + ": two samples of " +
                                          o.frames.front() + " fall in frame " + names[k] +
                                          " (samples below a frame): one file a frame cannot "
                                          "hold them; write the cache instead");
      plan.outputs[k] = (fs::path(o.output) / (names[k] + "." + format)).string();
      refuse_overwrite(plan.outputs[k], inputs);
    }
  }
  refuse_report_overwrite(o, inputs, plan.outputs);
  return plan;
}

namespace {

// The frame loop: the chosen frames on `threads` threads, each a pure function of its frame;
// per chosen frame its error, if it failed. Stops at the first failure unless --keep-going.
std::vector<std::unique_ptr<Error>> slide_frames(const RunOptions& o, const RunEvents& events,
                                                 const BindSetup& setup, const MeshFile& bind,
                                                 const FrameSource& source, CacheWriter* cache_out,
                                                 unsigned threads, RunReport& report) {
  const std::vector<size_t>& chosen = source.plan.chosen;
  const size_t count = chosen.size();
  const auto done = [&](size_t j, std::vector<LogLine> lines) {
    if (events.frame_done) events.frame_done(j, std::move(lines));
  };
  std::atomic<size_t> next{0};
  std::atomic<bool> stop{false};
  std::vector<std::unique_ptr<Error>> errors(count);
  if (!o.report.empty()) report.frames.resize(count);
  auto worker = [&] {
    for (size_t j; !stop && (j = next++) < count;) {
      const size_t i = chosen[j];
      const std::string& label = frame_label(o, source, i);
      const CacheSlot slot{cache_out, j};  // the chosen frames are one run of samples
      try {
        ReportFrame* record = o.report.empty() ? nullptr : &report.frames[j];
        done(j, run_source_frame(setup, bind, source, o, i, slot, record));
        continue;
      } catch (const Error& e) {
        errors[j] = std::make_unique<Error>(e);
      } catch (const std::bad_alloc&) {
        errors[j] = std::make_unique<Error>(ErrorKind::Internal, label + ": out of memory");
      } catch (const std::exception& e) {
        errors[j] = std::make_unique<Error>(ErrorKind::Internal, label + ": " + e.what());
      }
      // Fail fast by default: a farm task with a bad frame should fail, not half-succeed
      // (README "Exit codes"). --keep-going writes every good frame and names every bad one.
      if (o.keep_going)
        done(j, {});
      else
        stop = true;
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
  return errors;
}

// The JSON report, written last and atomically; --keep-going: it lists the frames written.
void write_run_report(const RunOptions& o, const BindSetup& setup, double wall_seconds,
                      RunReport& report) {
  report.bind = o.bind;
  report.patch_files = o.patches;
  report.timings = o.report_timings;
  report.wall_seconds = wall_seconds;
  std::erase_if(report.frames, [](const ReportFrame& r) { return r.output.empty(); });
  write_file_atomic(o.report, report_json(setup, report));
  const fs::path report_folder = fs::path(o.report).parent_path();
  sync_folder(report_folder.empty() ? "." : report_folder.string());
}

}  // namespace

RunResult run(const RunOptions& o, const RunEvents& events) {
  const auto log = [&](const LogLine& line) {
    if (events.log) events.log(line);
  };
  const auto t_run = std::chrono::steady_clock::now();
  // A rig run's frames are known once the character is read, a cache's once its header is;
  // their --frames is checked before.
  const bool cache_run = !o.rig && is_cache_run(o.frames);
  const bool files = !o.rig && !cache_run;
  if (!files) (void)frame_ranges(o);
  FramePlan files_plan = files ? plan_frames(o) : FramePlan{};
  if (files && (!o.dump_dir.empty() || !o.preview_dir.empty())) check_dump_stems(o.frames);

  // With --animation, BIND is a rigged glTF character: the bind is its mesh as stored.
  MeshFile bind = o.rig ? read_gltf_file(o.bind, {o.mesh}) : read_mesh_file(o.bind, {o.mesh});
  const FrameSource source = frame_source(o, bind, std::move(files_plan), cache_run);
  const FramePlan& plan = source.plan;
  std::vector<std::vector<Index>> selections;
  for (const std::string& p : o.patches)
    selections.push_back(selected_faces(read_patch(p), bind.mesh.face_count()));
  RunReport report;
  const SlideControls controls = slide_controls(o, bind, report);
  // The bind file's contents served the controls (vertex colours, attributes); from here on the
  // frames need only its mesh, unless it is the character the frames are posed from. At 1M
  // vertices an OBJ's text and token spans are about 70 MB held for the whole run. A cache's
  // frames written a file each are made from the bind's file.
  if (!o.rig && !(cache_run && plan.cache.empty())) {
    bind.obj.reset();
    bind.gltf.reset();
  }
  unsigned threads = o.threads == 0 ? usable_cores() : o.threads;
  // --no-slide measures the I/O floor of a run: no bind set-up, frames copied unchanged.
  const BindSetup setup =
      o.no_slide ? BindSetup{}
                 : bind_setup(
                       bind.mesh, selections, o.slide, controls,
                       [&](Index f) {
                         return "face " + std::to_string(f) + " (" + bind.where_face(f) + ")";
                       },
                       threads);
  report.bind_seconds = seconds_since(t_run);
  for (const LogLine& line : bind_lines(o, setup, controls)) log(line);
  make_output_dir(o.output);
  if (!o.dump_dir.empty())
    write_bind_dumps(o.dump_dir, o.bind, setup, bind.mesh.positions,
                     {.id_image_size = o.lookup_size});
  // A cache output is written sample by sample at its offsets, renamed into place once complete.
  std::unique_ptr<CacheWriter> cache_out;
  if (!plan.cache.empty())
    cache_out = std::make_unique<CacheWriter>(
        plan.cache, output_cache_header(o, plan, bind, source.clip, source.cache));

  const std::vector<size_t>& chosen = plan.chosen;
  const size_t count = chosen.size();
  threads = static_cast<unsigned>(std::min<size_t>(threads, count));
  log({LogLevel::Detail, "  " + std::to_string(count) + " frames, " + std::to_string(threads) +
                             " at a time" +
                             (o.threads == 0 ? " (-j 0: the cores this task may use)" : "")});
  if (events.frames_begin) events.frames_begin(count);
  std::vector<std::unique_ptr<Error>> errors =
      slide_frames(o, events, setup, bind, source, cache_out.get(), threads, report);
  if (events.frames_end) events.frames_end();
  // A cache has no holes: it appears only when every chosen frame is in it.
  const bool all_written =
      std::none_of(errors.begin(), errors.end(), [](const auto& e) { return e != nullptr; });
  if (cache_out && all_written) cache_out->commit();
  // Each output was flushed before its rename; flushing the folders makes the renames durable.
  // The preview folder is made with the first preview: when every frame failed before one,
  // there is nothing in it to flush, and the frames' errors below are the run's.
  for (const std::string& folder : {o.output, o.dump_dir, o.preview_dir}) {
    std::error_code ec;
    if (!folder.empty() && fs::is_directory(folder, ec)) sync_folder(folder);
  }
  RunResult result;
  result.frames = count;
  for (const auto& e : errors)
    if (e) {
      // The first bad frame in list order decides the exit code.
      if (!o.keep_going) throw *e;
      result.failures.push_back(*e);
      log({LogLevel::Error, std::string("skinslide: error: ") + e->what()});
    }
  if (cache_out && !all_written)
    log({LogLevel::Error, "skinslide: error: " + plan.cache +
                              ": not written: " + std::to_string(result.failures.size()) +
                              " of its samples failed, and a cache cannot have holes"});
  if (!o.report.empty()) write_run_report(o, setup, seconds_since(t_run), report);
  return result;
}

}  // namespace skinslide
