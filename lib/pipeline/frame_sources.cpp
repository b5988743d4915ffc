#include "pipeline/frame_sources.h"

#include <utility>

#include "core/error.h"
#include "core/number_format.h"
#include "core/stopwatch.h"
#include "io/atomic_write.h"
#include "io/gltf/gltf.h"
#include "io/mesh_formats.h"
#include "io/obj_rewrite.h"
#include "io/obj_write.h"
#include "pipeline/dumps.h"

namespace skinslide {
namespace {

// The first patch of a slid frame that did not converge, and why; none: result.patches.size().
std::pair<size_t, std::string> first_unconverged(const FrameResult& result) {
  for (size_t p = 0; p < result.patches.size(); ++p)
    if (std::string fault = convergence_fault(result.patches[p].method); !fault.empty())
      return {p, std::move(fault)};
  return {result.patches.size(), std::string()};
}

// slide_frame, with the frame named in its errors; with --require-converged a patch that did
// not converge fails the frame before anything of it is written.
FrameResult slide_named(const BindSetup& setup, const RunOptions& o, const Positions3& positions,
                        const std::string& name, const WindowedFrame* window) {
  FrameResult result = labelled(name, [&] {
    return slide_frame(
        setup, positions,
        {.id_image_size = o.dump_dir.empty() ? 0 : o.lookup_size, .edge_spread = !o.report.empty()},
        window);
  });
  if (o.require_converged)
    if (const auto [p, fault] = first_unconverged(result); !fault.empty())
      throw Error(ErrorKind::Numeric, name + ": patch " + std::to_string(p) +
                                          ": did not converge (" + fault +
                                          "; --require-converged)");
  return result;
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

// The frame's log lines, then its patches handed to the report's record (their nets dropped).
FrameOutcome finish_frame(const BindSetup& setup, FrameResult& result, const std::string& label,
                          const std::string& out_path, double read_seconds, double write_seconds,
                          ReportFrame* record) {
  FrameOutcome outcome{frame_lines(setup, result, label, out_path),
                       first_unconverged(result).second.empty(),
                       window_costly(setup, result.patches)};
  if (record)
    record_frame(*record, label, out_path, read_seconds, write_seconds, std::move(result.patches));
  return outcome;
}

// Reads, checks, slides and writes one frame; returns the log lines for it.
// A FRAME file's slide written where the plan says: its own slid file, or (--format pc2|mdd)
// its sample of the output cache, rounded to float32 once.
void write_file_frame(const MeshFile& frame, const SlidVertices& slid, const std::string& out_path,
                      CacheSlot slot) {
  if (slot.writer)
    return slot.writer->write_sample(slot.sample,
                                     positions_sample(apply_slide(frame.mesh.positions, slid)));
  write_slid_mesh_file(frame, slid, out_path);
}

// A FRAME file read and checked against the bind.
MeshFile read_frame_file(const MeshFile& bind, const RunOptions& o, const std::string& frame_path) {
  MeshFile frame = read_mesh_file(frame_path, mesh_read_options(o));
  require_same_topology(bind, frame);
  release_faces(frame);
  return frame;
}

FrameOutcome run_frame(const BindSetup& setup, const MeshFile& bind, const RunOptions& o,
                       const std::string& frame_path, const std::string& out_path, CacheSlot slot,
                       ReportFrame* record, const WindowedFrame* window) {
  auto t0 = Clock::now();
  MeshFile frame = read_frame_file(bind, o, frame_path);
  const double read_seconds = seconds_since(t0);
  if (o.no_slide) {
    write_file_frame(frame, SlidVertices{}, out_path, slot);
    return {
        {{LogLevel::Info, "skinslide: " + frame_path + ": unchanged (--no-slide) -> " + out_path}}};
  }
  FrameResult result = slide_named(setup, o, frame.mesh.positions, frame_path, window);
  write_frame_pictures(setup, o, frame_path, frame.mesh.positions, result);
  t0 = Clock::now();
  write_file_frame(frame, result.slid, out_path, slot);
  return finish_frame(setup, result, frame_path, out_path, read_seconds, seconds_since(t0), record);
}

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
// Sample k of a point cache as its errors name it.
std::string cache_label(const CacheFrames& cache, size_t k) {
  return cache.cache->path() + " sample " + std::to_string(k) + " (" + cache.names[k] + ")";
}

FrameOutcome run_cache_frame(const BindSetup& setup, const MeshFile& bind, const CacheFrames& cache,
                             const RunOptions& o, size_t k, const std::string& out_path,
                             CacheSlot slot, ReportFrame* record, const WindowedFrame* window) {
  const std::string label = cache_label(cache, k);
  auto t0 = Clock::now();
  CacheSample frame = cache.cache->sample(k);
  const Positions3 positions = sample_positions(frame);
  const double read_seconds = seconds_since(t0);
  FrameResult result;
  if (!o.no_slide) {
    result = slide_named(setup, o, positions, label, window);
    write_frame_pictures(setup, o, cache.names[k] + ".cache", positions, result);
  }
  t0 = Clock::now();
  write_cache_frame(bind, o, std::move(frame), positions, result.slid, out_path, slot, label);
  if (o.no_slide)
    return {{{LogLevel::Info, "skinslide: " + label + ": unchanged (--no-slide) -> " + out_path}}};
  return finish_frame(setup, result, label, out_path, read_seconds, seconds_since(t0), record);
}

// Frame k of a rigged character's clip: posed, slid, written as OBJ or GLB, or into a cache.
// Frame k of a clip as its errors name it.
std::string rig_label(const RigClip& clip, size_t k) {
  return clip.names[k] + " (t = " + log_number(clip.times[k]) + " s)";
}

FrameOutcome run_rig_frame(const BindSetup& setup, const MeshFile& character, const RigClip& clip,
                           const RunOptions& o, size_t k, const std::string& out_path,
                           CacheSlot slot, ReportFrame* record, const WindowedFrame* window) {
  const std::string label = rig_label(clip, k);
  auto t0 = Clock::now();
  const MeshFile frame = rig_frame(character, clip, k);
  const double pose_seconds = seconds_since(t0);
  FrameResult result = slide_named(setup, o, frame.mesh.positions, label, window);
  write_frame_pictures(setup, o, out_path, frame.mesh.positions, result);
  t0 = Clock::now();
  if (slot.writer)
    slot.writer->write_sample(slot.sample,
                              positions_sample(apply_slide(frame.mesh.positions, result.slid)));
  else if (o.format == "obj")
    write_file_atomic(out_path, obj_text(frame.mesh, apply_slide(frame.mesh.positions, result.slid),
                                         character.path + ", " + label + ", slid"));
  else
    write_gltf_file(frame, result.slid, out_path);
  return finish_frame(setup, result, label, out_path, pose_seconds, seconds_since(t0), record);
}

}  // namespace

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

CacheHeader output_cache_header(const RunOptions& o, const MeshFile& bind,
                                const FrameSource& source) {
  CacheHeader whole;
  if (source.cache.cache) {
    whole = source.cache.cache->header();
  } else if (o.rig) {
    whole = rig_cache_header(o.format == "pc2" ? CacheFormat::Pc2 : CacheFormat::Mdd,
                             bind.mesh.vertex_count(), source.clip.times);
  } else {  // FRAME files: the plan's header, of as many points as the bind has vertices
    whole = source.plan.whole;
    whole.points = bind.mesh.vertex_count();
  }
  return cache_output_header(whole, source.plan.chosen);
}

const std::string& frame_label(const RunOptions& o, const FrameSource& source, size_t i) {
  if (o.rig) return source.clip.names[i];
  return source.cache.cache ? source.cache.names[i] : o.frames[i];
}

FrameOutcome run_source_frame(const BindSetup& setup, const MeshFile& bind,
                              const FrameSource& source, const RunOptions& o, size_t i,
                              CacheSlot slot, ReportFrame* record, const WindowedFrame* window) {
  const std::string& out = source.plan.outputs[i];
  if (o.rig) return run_rig_frame(setup, bind, source.clip, o, i, out, slot, record, window);
  if (source.cache.cache)
    return run_cache_frame(setup, bind, source.cache, o, i, out, slot, record, window);
  return run_frame(setup, bind, o, o.frames[i], out, slot, record, window);
}

FrameRelaxations relax_source_frame(const BindSetup& setup, const MeshFile& bind,
                                    const FrameSource& source, const RunOptions& o, size_t i) {
  std::string label;
  Positions3 positions;
  if (o.rig) {
    label = rig_label(source.clip, i);
    positions = rig_frame(bind, source.clip, i).mesh.positions;
  } else if (source.cache.cache) {
    label = cache_label(source.cache, i);
    positions = sample_positions(source.cache.cache->sample(i));
  } else {
    label = o.frames[i];
    positions = read_frame_file(bind, o, label).mesh.positions;
  }
  return labelled(label, [&] { return relax_frame(setup, positions); });
}

}  // namespace skinslide
