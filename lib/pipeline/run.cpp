#include "pipeline/run.h"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <functional>
#include <filesystem>
#include <memory>
#include <new>
#include <optional>
#include <thread>
#include <utility>

#include "core/cores.h"
#include "core/stopwatch.h"
#include "io/atomic_write.h"
#include "io/gltf/gltf.h"
#include "io/mesh_formats.h"
#include "io/patch_file.h"
#include "io/run_inputs.h"
#include "pipeline/bind_setup.h"
#include "pipeline/controls.h"
#include "pipeline/dumps.h"
#include "pipeline/frame_sources.h"
#include "pipeline/frame_window.h"
#include "pipeline/input_checks.h"
#include "pipeline/report.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

void make_output_dir(const std::string& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw Error(ErrorKind::Output, dir + ": cannot write: exists and is not a folder");
  fs::create_directories(dir, ec);
  if (ec)
    throw Error(ErrorKind::Output, dir + ": cannot create the output folder: " + ec.message());
}

// The order of the run's frames for --window (none without a window or a slide).
std::optional<WindowPlan> run_window_plan(const RunOptions& o, const FrameSource& source) {
  if (o.window == 0 || o.no_slide) return std::nullopt;
  WindowPlan plan = o.rig                ? ordered_window_plan(o.window, source.clip.names.size())
                    : source.cache.cache ? ordered_window_plan(o.window, source.cache.names.size())
                                         : files_window_plan(o.window, o.frames);
  plan.cycle = o.window_ends == WindowEnds::Cycle;
  return plan;
}

// What a windowed run tells once about its ends (frame_window.h window_ends_line).
std::optional<LogLine> run_window_line(const RunOptions& o, const FrameSource& source,
                                       const std::optional<WindowPlan>& plan) {
  if (!plan) return std::nullopt;
  const bool files = !o.rig && !source.cache.cache;
  const std::vector<std::string>& labels = o.rig   ? source.clip.names
                                           : files ? o.frames
                                                   : source.cache.names;
  return window_ends_line(*plan, source.plan.chosen, labels,
                          files ? o.frames : std::vector<std::string>{}, o.frame_ranges);
}

// --window's relaxations of the run's frames, shared by the frame loop's threads; null without
// a window (or without a slide).
std::unique_ptr<RelaxationStore> relaxation_store(const RunOptions& o, const BindSetup& setup,
                                                  const MeshFile& bind, const FrameSource& source,
                                                  const std::optional<WindowPlan>& plan) {
  if (!plan) return nullptr;
  return std::make_unique<RelaxationStore>(*plan, source.plan.chosen, [&, o](size_t i) {
    return relax_source_frame(setup, bind, source, o, i);
  });
}

// Frame i of the run, slid (with its window's mean when `store`) and written.
FrameOutcome run_chosen_frame(const BindSetup& setup, const MeshFile& bind,
                              const FrameSource& source, const RunOptions& o, size_t i,
                              CacheSlot slot, ReportFrame* record, RelaxationStore* store) {
  if (!store) return run_source_frame(setup, bind, source, o, i, slot, record);
  const std::vector<RelaxationStore::Member> window = store->window(i);
  rethrow_window_error(window, i, frame_label(o, source, i));
  const WindowedFrame windowed = windowed_frame(window, i);
  return run_source_frame(setup, bind, source, o, i, slot, record, &windowed);
}

// What the frame loop's threads count.
struct RunCounts {
  std::atomic<size_t> not_converged{0};
  std::atomic<size_t> window_costly{0};
};

// The frame loop: the chosen frames on `threads` threads, each a pure function of its frame (and
// with --window of its window's relaxations, from `store`); per chosen frame its error in `errors`,
// if it failed. Stops at the first failure unless --keep-going. `errors` comes holding the frames
// already known to fail (a FRAME file that cannot be read, under --keep-going): they are told as
// failed, not read.
void slide_frames(const RunOptions& o, const RunEvents& events, const BindSetup& setup,
                  const MeshFile& bind, const FrameSource& source, RelaxationStore* store,
                  CacheWriter* cache_out, unsigned threads, RunReport& report, RunCounts& counts,
                  std::vector<std::unique_ptr<Error>>& errors) {
  const std::vector<size_t>& chosen = source.plan.chosen;
  const size_t count = chosen.size();
  const auto done = [&](size_t j, std::vector<LogLine> lines) {
    if (events.frame_done) events.frame_done(j, std::move(lines));
  };
  std::atomic<size_t> next{0};
  std::atomic<bool> stop{false};
  if (!o.report.empty()) report.frames.resize(count);
  auto worker = [&] {
    for (size_t j; !stop && (j = next++) < count;) {
      const size_t i = chosen[j];
      if (errors[j]) {
        if (store) store->done(i);
        done(j, {});
        continue;
      }
      const std::string& label = frame_label(o, source, i);
      const CacheSlot slot{cache_out, j};  // the chosen frames are one run of samples
      try {
        ReportFrame* record = o.report.empty() ? nullptr : &report.frames[j];
        FrameOutcome outcome = run_chosen_frame(setup, bind, source, o, i, slot, record, store);
        if (store) store->done(i);
        if (!outcome.converged) ++counts.not_converged;
        if (outcome.window_costly) ++counts.window_costly;
        done(j, std::move(outcome.lines));
        continue;
      } catch (const Error& e) {
        errors[j] = std::make_unique<Error>(e);
      } catch (const std::bad_alloc&) {
        errors[j] = std::make_unique<Error>(ErrorKind::Internal, label + ": out of memory");
      } catch (const std::exception& e) {
        errors[j] = std::make_unique<Error>(ErrorKind::Internal, label + ": " + e.what());
      }
      if (store) store->done(i);
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
}

// The run's first output in its folder: the cache, or the first chosen frame's file.
const std::string& first_output(const FramePlan& plan) {
  return plan.cache.empty() ? plan.outputs[plan.chosen.front()] : plan.cache;
}

// Per chosen frame, its error when its FRAME file cannot be read (check_inputs, --keep-going);
// every such file is told now, at once, before the bind is read (one that is only a --window
// neighbour too); `told` marks the chosen ones.
std::vector<std::unique_ptr<Error>> unreadable_chosen(
    const std::vector<UnreadableFrame>& bad, const FramePlan& plan, std::vector<bool>& told,
    const std::function<void(const LogLine&)>& log) {
  std::vector<std::unique_ptr<Error>> errors(plan.chosen.size());
  told.assign(plan.chosen.size(), false);
  std::vector<std::ptrdiff_t> slot(plan.outputs.size(), -1);
  for (size_t j = 0; j < plan.chosen.size(); ++j)
    slot[plan.chosen[j]] = static_cast<std::ptrdiff_t>(j);
  for (const UnreadableFrame& f : bad) {
    log({LogLevel::Error, std::string("skinslide: error: ") + f.error.what()});
    if (f.frame >= slot.size() || slot[f.frame] < 0) continue;
    const auto j = static_cast<size_t>(slot[f.frame]);
    errors[j] = std::make_unique<Error>(f.error);
    told[j] = true;
  }
  return errors;
}

}  // namespace

RunResult run(const RunOptions& given, const RunEvents& events) {
  RunOptions o = given;
  if (o.format.empty() && !is_cache_run(o.frames)) o.format = cache_format_named_by(o.output);
  // Whatever the run reads, no output of it replaces (io/run_inputs.h).
  const InputScope inputs;
  const auto log = [&](const LogLine& line) {
    if (events.log) events.log(line);
  };
  const auto t_run = Clock::now();
  // A rig run's frames are known once the character is read, a cache's once its header is;
  // their --frames is checked before.
  const bool cache_run = !o.rig && is_cache_run(o.frames);
  const bool files = !o.rig && !cache_run;
  if (!files) (void)frame_ranges(o);
  FramePlan files_plan = files ? plan_frames(o) : FramePlan{};
  if (files && (!o.dump_dir.empty() || !o.preview_dir.empty())) check_dump_stems(o.frames);
  // Every input looked at before any is read (input_checks.h): a missing frame fails now.
  const std::vector<UnreadableFrame> unreadable = check_inputs(o, files_plan.chosen);
  std::vector<bool> told;
  std::vector<std::unique_ptr<Error>> errors = unreadable_chosen(unreadable, files_plan, told, log);

  // With --animation, BIND is a rigged glTF character: the bind is its mesh as stored.
  const MeshReadOptions read_options = mesh_read_options(o);
  MeshFile bind =
      o.rig ? read_gltf_file(o.bind, read_options) : read_mesh_file(o.bind, read_options);
  const FrameSource source = frame_source(o, bind, std::move(files_plan), cache_run);
  const FramePlan& plan = source.plan;
  check_output_folder(plan.folder, first_output(plan));
  // --window's frame numbers are checked before the set-up too (a file without one is refused).
  const std::optional<WindowPlan> window_plan = run_window_plan(o, source);
  if (!files) errors.resize(plan.chosen.size());
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
                       threads, [&](Index s) { return "--patch " + o.patches[s]; });
  report.bind_seconds = seconds_since(t_run);
  for (const LogLine& line : bind_lines(o, setup, controls)) log(line);
  if (const std::optional<LogLine> line = run_window_line(o, source, window_plan)) log(*line);
  make_output_dir(plan.folder);
  if (!o.dump_dir.empty())
    write_bind_dumps(o.dump_dir, o.bind, setup, bind.mesh.positions,
                     {.id_image_size = o.lookup_size});
  // A cache output is written sample by sample at its offsets, renamed into place once complete.
  std::unique_ptr<CacheWriter> cache_out;
  if (!plan.cache.empty())
    cache_out = std::make_unique<CacheWriter>(plan.cache, output_cache_header(o, bind, source));

  const std::vector<size_t>& chosen = plan.chosen;
  const size_t count = chosen.size();
  threads = static_cast<unsigned>(std::min<size_t>(threads, count));
  log({LogLevel::Detail, "  " + std::to_string(count) + " frames, " + std::to_string(threads) +
                             " at a time" +
                             (o.threads == 0 ? " (-j 0: the cores this task may use)" : "")});
  if (events.frames_begin) events.frames_begin(count);
  RunCounts counts;
  const std::unique_ptr<RelaxationStore> store =
      relaxation_store(o, setup, bind, source, window_plan);
  slide_frames(o, events, setup, bind, source, store.get(), cache_out.get(), threads, report,
               counts, errors);
  if (events.frames_end) events.frames_end();
  // A cache has no holes: it appears only when every chosen frame is in it.
  const bool all_written =
      std::none_of(errors.begin(), errors.end(), [](const auto& e) { return e != nullptr; });
  if (cache_out && all_written) cache_out->commit();
  // Each output was flushed before its rename; flushing the folders makes the renames durable.
  // The preview folder is made with the first preview: when every frame failed before one,
  // there is nothing in it to flush, and the frames' errors below are the run's.
  for (const std::string& folder : {plan.folder, o.dump_dir, o.preview_dir}) {
    std::error_code ec;
    if (!folder.empty() && fs::is_directory(folder, ec)) sync_folder(folder);
  }
  RunResult result;
  result.frames = count;
  result.not_converged = counts.not_converged;
  result.window_costly = counts.window_costly;
  for (size_t j = 0; j < errors.size(); ++j)
    if (const auto& e = errors[j]) {
      // The first bad frame in list order decides the exit code.
      if (!o.keep_going) throw *e;
      result.failures.push_back(*e);
      if (j >= told.size() || !told[j])
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
