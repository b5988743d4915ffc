// Farm chunks of a point cache (lib/io/README.md "Point caches"): a task that slides some of a
// shot's samples writes a cache of its own, named after its first and last frame
// (`shot.0101-0200.pc2`), and the chunks join into the whole shot's cache, byte for byte what
// one task sliding every sample writes.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "io/point_cache.h"

namespace skinslide {

/// The header of samples [first, first + count) of `whole`: the same points; PC2: the same rate
/// and startFrame the frame of sample `first` (startFrame itself for first = 0, else
/// startFrame + first x sampleRate computed in double and rounded to float32 once); MDD: those
/// samples' times. \pre first + count <= whole.samples, count > 0.
CacheHeader chunk_header(const CacheHeader& whole, std::size_t first, std::size_t count);

/// The file name of a chunk whose samples run from frame `first` to frame `last`:
/// `<stem>.<first>-<last><extension>`, each frame number zero-padded to 4 digits (more when
/// needed): ("shot", 101, 200, ".pc2") -> "shot.0101-0200.pc2".
std::string chunk_file_name(const std::string& stem, long long first, long long last,
                            const std::string& extension);

/// The parts of a chunk's file name, as chunk_file_name makes them.
struct ChunkName {
  std::string stem;       ///< "shot"
  long long first = 0;    ///< first frame
  long long last = 0;     ///< last frame
  std::string extension;  ///< ".pc2"
};

/// The parts of `path`'s file name; nullopt when it is not `<stem>.<digits>-<digits>.<ext>`
/// with first <= last.
std::optional<ChunkName> parse_chunk_name(const std::string& path);

/// What join_cache_chunks wrote.
struct JoinResult {
  std::string output;  ///< OUTPUT_DIR/<stem><extension>
  CacheHeader header;  ///< the joined cache's header
  std::size_t chunks = 0;
};

/// Joins chunk caches (in any order) into `output_dir`/<stem><extension>, written atomically:
/// the header of the first chunk (by frame) with every chunk's samples, in frame order, copied
/// bit for bit. Every chunk is read and checked as a frame source is (io/point_cache.h), and
/// together they must be one run of samples: names as chunk_file_name makes them, one stem and
/// format, the same point count (and PC2 sample rate), no overlap and no gap (PC2: each chunk
/// starts one sample after the one before it ends; MDD: frame numbers, the sample indices,
/// follow on, and the times keep increasing), each name's frames those of its header (PC2) or
/// sample count (MDD). A missing first or last chunk cannot be told from a shorter shot.
/// \throw Error(Usage) for no chunks; Error(Input) naming the chunk for anything else;
///        Error(Output) when the output cannot be written.
JoinResult join_cache_chunks(const std::vector<std::string>& chunks, const std::string& output_dir);

}  // namespace skinslide
