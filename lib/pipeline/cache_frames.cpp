#include "pipeline/cache_frames.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/check.h"
#include "core/error.h"
#include "io/cache_chunks.h"
#include "io/gltf/gltf.h"
#include "pipeline/frame_ranges.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kFrameDigits = 4;  // shot.0001.obj, as frame files are numbered

std::string frame_name(const std::string& stem, long long frame) {
  const std::string digits = std::to_string(frame < 0 ? -frame : frame);
  return stem + "." + (frame < 0 ? "-" : "") +
         std::string(kFrameDigits > digits.size() ? kFrameDigits - digits.size() : 0, '0') + digits;
}

}  // namespace

bool is_cache_run(const std::vector<std::string>& frames) {
  const auto is_cache = [](const std::string& f) { return cache_format(f).has_value(); };
  const auto caches = std::count_if(frames.begin(), frames.end(), is_cache);
  if (caches == 0) return false;
  if (frames.size() > 1)
    throw Error(ErrorKind::Usage, "a point cache is a whole shot: give it as the only FRAME (" +
                                      *std::find_if(frames.begin(), frames.end(), is_cache) +
                                      " with " + std::to_string(frames.size() - 1) +
                                      " other FRAMEs)");
  return true;
}

bool is_cache_format(const std::string& format) { return format == "pc2" || format == "mdd"; }

CacheFrames open_cache_frames(const std::string& path, const MeshFile& bind) {
  CacheFrames frames;
  auto cache = std::make_shared<const CacheReader>(path);
  const Index points = cache->header().points;
  const Index vertices = bind.mesh.vertex_count();
  if (points != vertices) {
    std::string what = "has " + std::to_string(points) + " points; the bind (" + bind.path +
                       ") has " + std::to_string(vertices) + " vertices";
    if (bind.gltf && points == gltf_raw_vertex_count(bind))
      what += ". " + std::to_string(points) +
              " is the bind's count of raw glTF vertices, before welding: the order of a "
              "cache over them is ambiguous (seams split vertices), so it is refused; a cache "
              "holds one point per welded vertex, in skinslide's order";
    else
      what += ": a cache must hold one point per bind vertex, in the bind's order";
    throw Error(ErrorKind::Input, path + ": " + what);
  }
  const std::string stem = fs::path(path).stem().string();
  for (std::size_t k = 0; k < static_cast<std::size_t>(cache->header().samples); ++k)
    frames.names.push_back(frame_name(stem, sample_frame(cache->header(), k)));
  frames.cache = std::move(cache);
  return frames;
}

std::vector<std::size_t> chosen_samples(const CacheHeader& header,
                                        const std::string& frame_ranges) {
  const std::size_t samples = static_cast<std::size_t>(header.samples);
  std::vector<std::size_t> chosen;
  if (frame_ranges.empty()) {
    for (std::size_t k = 0; k < samples; ++k) chosen.push_back(k);
    return chosen;
  }
  const std::vector<FrameRange> ranges = parse_frame_ranges(frame_ranges);
  for (std::size_t k = 0; k < samples; ++k)
    if (in_frame_ranges(ranges, sample_frame(header, k))) chosen.push_back(k);
  if (chosen.empty())
    throw Error(ErrorKind::Usage, "--frames " + frame_ranges + " selects none of the cache's " +
                                      std::to_string(samples) + " samples (frames " +
                                      std::to_string(sample_frame(header, 0)) + " to " +
                                      std::to_string(sample_frame(header, samples - 1)) + ")");
  return chosen;
}

std::string cache_output_path(const std::string& output_dir, const std::string& stem,
                              const std::string& extension, const CacheHeader& whole,
                              const std::vector<std::size_t>& chosen) {
  SKINSLIDE_CHECK(!chosen.empty(), "a cache of at least one sample");
  if (chosen.back() - chosen.front() + 1 != chosen.size())
    throw Error(ErrorKind::Usage,
                "--frames selects samples with gaps between them (frames " +
                    std::to_string(sample_frame(whole, chosen.front())) + " to " +
                    std::to_string(sample_frame(whole, chosen.back())) + ", " +
                    std::to_string(chosen.size()) +
                    " samples): a cache holds one run of samples; give a range without a step "
                    "or list, or write one file a frame (--format obj or glb)");
  const std::string name = chosen.size() == static_cast<std::size_t>(whole.samples)
                               ? stem + extension
                               : chunk_file_name(stem, sample_frame(whole, chosen.front()),
                                                 sample_frame(whole, chosen.back()), extension);
  return (fs::path(output_dir) / name).string();
}

CacheHeader cache_output_header(const CacheHeader& whole, const std::vector<std::size_t>& chosen) {
  return chunk_header(whole, chosen.front(), chosen.size());
}

CacheHeader rig_cache_header(CacheFormat format, Index points, const std::vector<double>& times) {
  CacheHeader h;
  h.format = format;
  h.points = points;
  h.samples = static_cast<std::int32_t>(times.size());
  if (format == CacheFormat::Pc2) return h;  // startFrame 0, sampleRate 1: frames from 0
  for (std::size_t k = 0; k < times.size(); ++k) {
    h.times.push_back(static_cast<float>(times[k]));
    if (k > 0 && !(h.times[k] > h.times[k - 1]))
      throw Error(ErrorKind::Usage, "--format mdd: the clip's samples " + std::to_string(k - 1) +
                                        " and " + std::to_string(k) +
                                        " have one time in float32 (MDD times are float32 "
                                        "seconds): sample the clip less densely (--fps)");
  }
  return h;
}

CacheSample slid_sample(CacheSample frame, const SlidVertices& slid) {
  for (std::size_t k = 0; k < slid.vertex.size(); ++k) {
    const std::size_t v = static_cast<std::size_t>(slid.vertex[k]);
    SKINSLIDE_CHECK(3 * v + 2 < frame.size(), "a slid vertex of the frame");
    for (int c = 0; c < 3; ++c) frame[3 * v + c] = static_cast<float>(slid.position[k][c]);
  }
  return frame;
}

CacheSample positions_sample(const Positions3& positions) {
  CacheSample sample(3 * positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v)
    for (int c = 0; c < 3; ++c) sample[3 * v + c] = static_cast<float>(positions[v][c]);
  return sample;
}

}  // namespace skinslide
