#include "pipeline/frame_plans.h"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <set>
#include <unordered_map>

#include "core/error.h"
#include "core/file_extension.h"
#include "core/number_format.h"
#include "io/file_key.h"
#include "pipeline/cache_frames.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

// Every file a run reads, by the file it is (io/file_key.h): no output may be one of them. Each
// path is looked at once, so a plan of n frames is O(n).
struct Inputs {
  FileKeys keys;
  std::unordered_map<FileKey, std::string, FileKeyHash> read;  // key -> the input's path
};

void add_input(Inputs& inputs, const std::string& path) {
  inputs.read.emplace(inputs.keys.key(path, ErrorKind::Input), path);
}

Inputs run_inputs(const RunOptions& o) {
  Inputs inputs;
  for (const std::string& f : o.frames) add_input(inputs, f);
  add_input(inputs, o.bind);
  for (const std::string& p : o.patches) add_input(inputs, p);
  for (const std::string* f : {&o.weights, &o.pin})
    if (!f->empty()) add_input(inputs, *f);
  return inputs;
}

// The input `target` would replace, if any.
const std::string* input_at(Inputs& inputs, const std::string& target) {
  const auto found = inputs.read.find(inputs.keys.key(target, ErrorKind::Output));
  return found == inputs.read.end() ? nullptr : &found->second;
}

void refuse_overwrite(const std::string& target, Inputs& inputs) {
  if (const std::string* in = input_at(inputs, target))
    throw Error(ErrorKind::Usage, "output " + target + " would overwrite input " + *in +
                                      "; choose another --output folder");
}

// A cache output and, for a chunk, the shot's cache its join makes in that folder
// (`skinslide join`): neither may be an input, or the join would replace the shot it came from.
void refuse_cache_overwrite(const std::string& cache, const std::string& joined, Inputs& inputs) {
  refuse_overwrite(cache, inputs);
  if (cache == joined) return;
  if (const std::string* in = input_at(inputs, joined))
    throw Error(ErrorKind::Usage, "output " + cache + ": its chunks would join into " + joined +
                                      ", which is input " + *in +
                                      "; choose another --output folder");
}

// The report must overwrite neither an input nor an output.
void refuse_report_overwrite(const RunOptions& o, Inputs& inputs,
                             const std::vector<std::string>& outputs) {
  if (o.report.empty()) return;
  std::error_code ec;
  if (fs::exists(o.report, ec) && !fs::is_regular_file(o.report, ec))
    throw Error(ErrorKind::Usage, "--report " + o.report +
                                      " is not a regular file (a device, a pipe or a socket), "
                                      "which writing the report would replace; name a file");
  if (const std::string* in = input_at(inputs, o.report))
    throw Error(ErrorKind::Usage, "--report " + o.report + " would overwrite input " + *in);
  const FileKey report = inputs.keys.key(o.report, ErrorKind::Output);
  const std::string* last = nullptr;  // a cache's outputs are one path, looked at once
  for (const std::string& f : outputs) {
    if (f.empty() || (last && f == *last)) continue;
    last = &f;
    if (inputs.keys.key(f, ErrorKind::Output) == report)
      throw Error(ErrorKind::Usage, "--report " + o.report + " is also the output of a frame");
  }
}

// An -o named like a mesh (`-o shot.obj`) is taken for a file, but names the folder the frames
// go to under their own names.
void refuse_mesh_output(const RunOptions& o) {
  const std::string ext = lower_extension(o.output);
  if (ext == ".obj" || ext == ".gltf" || ext == ".glb")
    throw Error(ErrorKind::Usage,
                "-o " + o.output +
                    ": -o is a folder, not a mesh file: the slid frames keep "
                    "their own names in it (-o slid/); one file for a shot is a point cache (-o "
                    "shot.pc2)");
}

// Why a point cache is written in its own format, never converted.
constexpr const char* kCacheKeepsItsFormat =
    "(PC2 frames and MDD times do not convert without a frame rate)";

// An -o named as a cache of the other format (`-o shot.mdd` for a PC2 run) is refused, not made
// a folder of that name. `writes`: why the run writes `format`.
void refuse_other_cache_output(const RunOptions& o, const std::string& format,
                               const std::string& writes) {
  const std::string named = cache_format_named_by(o.output);
  if (!named.empty() && named != format)
    throw Error(ErrorKind::Usage,
                "-o " + o.output + ": names a " + named + " cache, but " + writes);
}

// refuse_other_cache_output for a run whose --format chose the cache.
void refuse_other_cache_output(const RunOptions& o, const std::string& format) {
  refuse_other_cache_output(
      o, format, "--format " + format + " writes a " + format + " cache: give one of them");
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

// A BIND named like the FRAMEs is most likely the sequence's first frame with the bind left out
// (`skinslide --patch p.txt frames/*.obj`): the run would slide every other frame against it.
void refuse_bind_in_sequence(const RunOptions& o) {
  if (o.bind_is_frame) return;
  const std::optional<std::string> bind = frame_sequence(o.bind);
  if (!bind) return;
  for (const std::string& f : o.frames)
    if (frame_sequence(f) == bind)
      throw Error(ErrorKind::Usage,
                  "BIND " + o.bind + " is named as a frame of the sequence it comes with (" + f +
                      (o.frames.size() > 1 ? ", ..." : "") +
                      "): is the bind mesh missing? Give the bind before the frames, or "
                      "--bind-is-frame if this frame is meant as the bind");
}

// The name of a sequence's cache: the first frame's stem without its number and the separator
// before it (`arm.0001.obj` -> `arm`).
std::string sequence_stem(const std::string& first) {
  std::string stem = fs::path(first).stem().string();
  if (const std::optional<std::string> sequence = frame_sequence(first)) {  // `arm.#.obj`
    stem = fs::path(*sequence).stem().string();
    stem.erase(stem.find('#'), 1);
  }
  while (!stem.empty() && (stem.back() == '.' || stem.back() == '_' || stem.back() == '-'))
    stem.pop_back();
  return stem.empty() ? "frames" : stem;
}

// The header of FRAME files written as one cache, from their frame numbers (README "Point
// caches"): PC2 holds a start and a step, MDD a time a sample.
CacheHeader sequence_cache_header(const RunOptions& o) {
  const std::string& format = o.format;
  std::vector<long long> numbers;
  for (const std::string& f : o.frames)
    if (const auto n = frame_number(f)) numbers.push_back(*n);
  if (!numbers.empty() && numbers.size() != o.frames.size())
    throw Error(ErrorKind::Usage, "--format " + format +
                                      ": some FRAMEs have a frame number in their file names "
                                      "and some have not; a cache's samples need one or the "
                                      "other (name them all name.0001.obj ...)");
  if (numbers.empty())
    for (std::size_t k = 0; k < o.frames.size(); ++k) numbers.push_back(static_cast<long long>(k));
  CacheHeader h;
  h.format = format == "pc2" ? CacheFormat::Pc2 : CacheFormat::Mdd;
  h.samples = static_cast<std::int32_t>(o.frames.size());
  if (h.format == CacheFormat::Mdd && !(o.fps > 0))
    throw Error(ErrorKind::Usage,
                "--format mdd: an MDD cache holds each sample's time in seconds: give the "
                "frames' rate with --fps (frame n at n / fps)");
  const long long step = numbers.size() > 1 ? numbers[1] - numbers[0] : 1;
  for (std::size_t k = 1; k < numbers.size(); ++k) {
    const bool pc2_ok = numbers[k] - numbers[k - 1] == step && step > 0;
    if (h.format == CacheFormat::Pc2 ? !pc2_ok : !(numbers[k] > numbers[k - 1]))
      throw Error(ErrorKind::Usage,
                  "--format " + format + ": " + o.frames[k] + " (frame " +
                      std::to_string(numbers[k]) + ") follows " + o.frames[k - 1] + " (frame " +
                      std::to_string(numbers[k - 1]) + ")" +
                      (h.format == CacheFormat::Pc2
                           ? ": a PC2 cache's frames rise by one step (startFrame, sampleRate); "
                             "give the frames in order, evenly numbered, or write MDD"
                           : ": an MDD cache's times rise; give the frames in order"));
  }
  if (h.format == CacheFormat::Pc2) {
    h.start_frame = static_cast<float>(numbers.front());
    h.sample_rate = static_cast<float>(step);
    return h;
  }
  for (std::size_t k = 0; k < numbers.size(); ++k) {
    h.times.push_back(static_cast<float>(static_cast<double>(numbers[k]) / o.fps));
    if (k > 0 && !(h.times[k] > h.times[k - 1]))
      throw Error(ErrorKind::Usage, "--format mdd: frames " + std::to_string(numbers[k - 1]) +
                                        " and " + std::to_string(numbers[k]) +
                                        " have one time in float32 at --fps " +
                                        format_double(o.fps) + "; give the frames' own rate");
  }
  return h;
}

}  // namespace

CacheTarget cache_target(const std::string& output, const std::string& stem,
                         const std::string& extension) {
  const fs::path out(output);
  if (lower_extension(output) == lower_extension("cache" + extension) && !out.stem().empty()) {
    const std::string folder = out.parent_path().string();
    return {folder.empty() ? "." : folder, out.stem().string()};
  }
  return {output, stem};
}

std::string cache_format_named_by(const std::string& output) {
  const std::string ext = lower_extension(output);
  if (fs::path(output).stem().empty()) return "";
  return ext == ".pc2" ? "pc2" : ext == ".mdd" ? "mdd" : "";
}

std::vector<FrameRange> frame_ranges(const RunOptions& o) {
  return o.frame_ranges.empty() ? std::vector<FrameRange>{} : parse_frame_ranges(o.frame_ranges);
}

FramePlan plan_frames(const RunOptions& o) {
  refuse_bind_in_sequence(o);
  refuse_mesh_output(o);
  const std::vector<FrameRange> ranges = frame_ranges(o);
  Inputs inputs = run_inputs(o);
  FramePlan plan;
  plan.folder = o.output;
  if (is_cache_format(o.format)) {
    refuse_other_cache_output(o, o.format);
    plan.whole = sequence_cache_header(o);
    plan.chosen = chosen_frames(ranges, o.frames, o.frames, o.frame_ranges);
    const std::string extension = "." + o.format;
    const CacheTarget target = cache_target(o.output, sequence_stem(o.frames.front()), extension);
    plan.folder = target.folder;
    plan.cache = cache_output_path(target.folder, target.stem, extension, plan.whole, plan.chosen);
    refuse_cache_overwrite(plan.cache,
                           (fs::path(target.folder) / (target.stem + extension)).string(), inputs);
    plan.outputs.assign(o.frames.size(), plan.cache);
    refuse_report_overwrite(o, inputs, plan.outputs);
    return plan;
  }
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
  refuse_mesh_output(o);
  const std::vector<FrameRange> ranges = frame_ranges(o);
  Inputs inputs;
  add_input(inputs, o.bind);
  for (const std::string& p : o.patches) add_input(inputs, p);
  const std::string format = o.format.empty() ? "glb" : o.format;
  FramePlan plan;
  plan.folder = o.output;
  for (const std::string& name : names) {
    const std::string target = (fs::path(o.output) / (name + "." + format)).string();
    refuse_overwrite(target, inputs);
    plan.outputs.push_back(target);
  }
  plan.chosen = chosen_frames(ranges, plan.outputs, names, o.frame_ranges);
  if (is_cache_format(format)) {
    refuse_other_cache_output(o, format);
    // The clip's frames as samples of one cache: frame numbers are the sample indices.
    CacheHeader whole;
    whole.format = format == "pc2" ? CacheFormat::Pc2 : CacheFormat::Mdd;
    whole.samples = static_cast<std::int32_t>(names.size());
    const std::string extension = "." + format;
    const CacheTarget target = cache_target(o.output, fs::path(o.bind).stem().string(), extension);
    plan.folder = target.folder;
    plan.cache = cache_output_path(target.folder, target.stem, extension, whole, plan.chosen);
    refuse_cache_overwrite(plan.cache,
                           (fs::path(target.folder) / (target.stem + extension)).string(), inputs);
    plan.outputs.assign(names.size(), plan.cache);
  }
  return plan;
}

FramePlan plan_cache_frames(const RunOptions& o, const CacheHeader& cache,
                            const std::vector<std::string>& names) {
  refuse_mesh_output(o);
  Inputs inputs = run_inputs(o);
  const std::string own = to_string(cache.format);
  const std::string format = o.format.empty() ? own : o.format;
  FramePlan plan;
  plan.folder = o.output;
  plan.chosen = chosen_samples(cache, o.frame_ranges);
  if (is_cache_format(format)) {
    if (format != own)
      throw Error(ErrorKind::Usage, "--format " + format + ": " + o.frames.front() + " is a " +
                                        own + " cache; a cache is written in its own format " +
                                        kCacheKeepsItsFormat);
    refuse_other_cache_output(o, own,
                              o.frames.front() + " is a " + own +
                                  " cache, written in its own format " + kCacheKeepsItsFormat);
    const fs::path input(o.frames.front());
    const std::string extension = input.extension().string();
    const CacheTarget target = cache_target(o.output, input.stem().string(), extension);
    plan.folder = target.folder;
    plan.cache = cache_output_path(target.folder, target.stem, extension, cache, plan.chosen);
    refuse_cache_overwrite(plan.cache,
                           (fs::path(target.folder) / (target.stem + extension)).string(), inputs);
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

}  // namespace skinslide
