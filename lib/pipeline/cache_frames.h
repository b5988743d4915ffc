// A point cache (PC2, MDD; io/point_cache.h) as a run's frames, and as a run's output: which
// samples --frames selects, the names of their frames, the header of the cache a run writes, and
// the conversions between a cache's float32 samples and the double positions the slide works on.
// README "Point caches"; every rule in lib/io/README.md "Point caches".
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "core/types.h"
#include "io/mesh_file.h"
#include "io/point_cache.h"
#include "mesh/slid_vertices.h"

namespace skinslide {

/// True when the run's FRAMEs are one point cache (one FRAME named .pc2 or .mdd).
/// \throw Error(Usage) for a cache among other FRAMEs: a run has one frame source.
bool is_cache_run(const std::vector<std::string>& frames);

/// True for the output formats that are point caches: "pc2", "mdd".
bool is_cache_format(const std::string& format);

/// A cache opened as the frames of `bind`.
struct CacheFrames {
  std::shared_ptr<const CacheReader> cache;
  /// Per sample, the name of its frame: "<cache stem>.<frame>" with the frame number
  /// (io/point_cache.h sample_frame) zero-padded to 4 digits: the per-frame outputs' and dumps'
  /// names, and the log's. Two samples in one whole frame (a PC2 sampled below a frame) share it.
  std::vector<std::string> names;
};

/// Opens `path` as the frames of `bind`: its point count must be the bind's vertex count (OBJ:
/// one point per `v` line, in order; glTF: one per welded vertex, in skinslide's welded order).
/// \throw Error(Input) for a bad cache (io/point_cache.h) or a point count that is not the
///        bind's, naming both (and, for a glTF bind whose seams split vertices, saying when the
///        count is the raw, unwelded one: that order is ambiguous and refused).
CacheFrames open_cache_frames(const std::string& path, const MeshFile& bind);

/// The samples (ascending indices) whose frames --frames names; every sample for empty ranges.
/// A range past the cache's frames selects what there is (a farm's last chunk may overshoot).
/// \throw Error(Usage) for a malformed --frames, or one that selects no sample.
std::vector<std::size_t> chosen_samples(const CacheHeader& header, const std::string& frame_ranges);

/// The file a run writes its chosen samples to, in `output_dir`: `<stem><extension>` when it
/// slides every sample of `samples`, else the chunk `<stem>.<first>-<last><extension>` named by
/// its first and last frame (io/cache_chunks.h).
/// \throw Error(Usage) for a chunk that is not one run of samples (--frames 1-100:5 skips some):
///        a cache cannot have holes.
std::string cache_output_path(const std::string& output_dir, const std::string& stem,
                              const std::string& extension, const CacheHeader& whole,
                              const std::vector<std::size_t>& chosen);

/// The header of the cache a run writes from the samples `chosen` (one run of them) of `whole`.
CacheHeader cache_output_header(const CacheHeader& whole, const std::vector<std::size_t>& chosen);

/// The whole cache a --animation run's frames make: `points` vertices; PC2 frame numbers are
/// the sample indices (startFrame 0, sampleRate 1, as the per-frame files count from 0); MDD
/// times the clip's sample times, rounded to float32.
/// \throw Error(Usage) when two sample times round to one float32 (an --fps too high).
CacheHeader rig_cache_header(CacheFormat format, Index points, const std::vector<double>& times);

/// The sample to write for a frame whose unslid coordinates are `frame` (3 x #V floats): the
/// vertices of `slid` at their slid positions, rounded to float32 once; every other vertex's
/// coordinates copied bit for bit.
CacheSample slid_sample(CacheSample frame, const SlidVertices& slid);

/// `positions` rounded to float32, as a sample.
CacheSample positions_sample(const Positions3& positions);

}  // namespace skinslide
