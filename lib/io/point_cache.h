// Point caches in and out: PC2 (3ds Max Point Cache 2; Blender, Maya, the FBX SDK) and MDD
// (LightWave; Houdini, Blender, Modo). Every byte is described in lib/io/README.md "Point
// caches"; in short:
//   PC2, little-endian: char[12] "POINTCACHE2\0", int32 version (1), int32 points,
//        float32 startFrame, float32 sampleRate, int32 samples (32 bytes), then
//        samples x points x (x, y, z) float32.
//   MDD, big-endian: int32 samples, int32 points, float32 times[samples] (seconds), then
//        samples x points x (x, y, z) float32.
// A cache is read and written one sample at a time (a 1000-sample cache of 100k points is
// 1.2 GB): the reader checks the header against the file's size before it allocates anything,
// and threads may read samples at once; the writer puts each sample at its own offset, so the
// samples may come in any order and the bytes never depend on it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/types.h"
#include "io/atomic_write.h"

namespace skinslide {

enum class CacheFormat { Pc2, Mdd };

/// The cache format a file name says: `.pc2` or `.mdd` (any case); nullopt for anything else.
std::optional<CacheFormat> cache_format(const std::string& path);

/// "pc2" or "mdd".
const char* to_string(CacheFormat format);

/// A cache's header as plain data. Fields of the other format are left at their defaults.
struct CacheHeader {
  CacheFormat format = CacheFormat::Pc2;
  std::int32_t points = 0;   ///< vertices per sample
  std::int32_t samples = 0;  ///< samples (PC2 numSamples, MDD frames)
  float start_frame = 0;     ///< PC2: frame number of sample 0
  float sample_rate = 1;     ///< PC2: frames from one sample to the next
  std::vector<float> times;  ///< MDD: each sample's time in seconds (#samples, increasing)
};

/// x y z of every point of one sample, in point order: 3 x points floats.
using CacheSample = std::vector<float>;

constexpr std::uint64_t kPc2HeaderBytes = 32;
constexpr std::uint64_t kMddCountBytes = 8;      ///< MDD's two counts, before its times
constexpr std::uint64_t kBytesPerPoint = 3 * 4;  ///< x, y, z as float32

/// Bytes before the first sample: 32 (PC2) or 8 + 4 x samples (MDD).
std::uint64_t header_bytes(const CacheHeader& header);
/// Byte offset of sample `k`'s first coordinate.
std::uint64_t sample_offset(const CacheHeader& header, std::size_t k);
/// The size of the whole file the header describes.
std::uint64_t cache_bytes(const CacheHeader& header);
/// The header as the file stores it (header_bytes(header) bytes).
/// \pre a header that check_cache_header accepts.
std::string encode_header(const CacheHeader& header);

/// A sample as the file stores it (12 x points bytes in the format's byte order), bit for bit.
/// \throw Error(Numeric) naming `path`, the sample `k` and the point of a coordinate that is not
///        finite (a cache never holds one).
std::string encode_sample(const std::string& path, CacheFormat format, std::size_t k,
                          const CacheSample& xyz);

/// A sample's coordinates as positions (float32 to double: exact).
Positions3 sample_positions(const CacheSample& sample);

/// The whole frame sample `k` belongs to. PC2: startFrame + k x sampleRate, rounded down, or to
/// the nearest whole frame when within 1e-4 of it (Blender's FRAME_SNAP_EPS: a rate of 0.01 is
/// not exact in float32); MDD, whose header has no frame numbers: `k`, the sample index from 0.
long long sample_frame(const CacheHeader& header, std::size_t k);

/// Parses a header from the file's first bytes (`head`: at least header_bytes of it, or the
/// whole file when shorter) and checks it against the file's size: the format's magic and
/// version, counts above zero, a size that is exactly the header's, finite PC2 start and rate
/// with the rate above zero, finite MDD times each after the one before.
/// \throw Error(Input) "path: what" (with the byte offset where it helps) for any of those.
CacheHeader parse_cache_header(const std::string& path, CacheFormat format, std::string_view head,
                               std::uint64_t file_size);

/// A cache read sample by sample, from a file or from bytes in memory (tests, fuzzing).
/// Holds a file descriptor (or the bytes) and the checked header, never the samples.
class CacheReader {
 public:
  /// Opens `path` (format from its name) and checks its header against its size.
  /// \throw Error(Usage) for a name that is neither .pc2 nor .mdd; Error(Input) for a file that
  ///        cannot be read or a bad header (parse_cache_header).
  explicit CacheReader(const std::string& path);
  /// The same over `bytes`, named `path` in errors.
  CacheReader(const std::string& path, CacheFormat format, std::string bytes);
  ~CacheReader();
  CacheReader(const CacheReader&) = delete;
  CacheReader& operator=(const CacheReader&) = delete;

  const std::string& path() const { return path_; }
  const CacheHeader& header() const { return header_; }

  /// Sample `k`'s coordinates, decoded bit for bit. Safe to call from several threads.
  /// \throw Error(Input) naming the sample, point and byte offset of a NaN or infinite
  ///        coordinate, or when the file cannot be read (it shrank since it was opened).
  CacheSample sample(std::size_t k) const;

 private:
  CacheHeader read_header(CacheFormat format) const;
  void read_at(std::uint64_t offset, char* out, std::size_t size) const;

  std::string path_;
  CacheHeader header_;
  int fd_ = -1;
  std::string bytes_;  // the cache itself when read from memory
};

/// A cache written sample by sample: the header when opened, each sample at its offset (any
/// order, from any thread), the file renamed into place by commit() once every sample is there.
/// Destroyed before that (an error on the way), it leaves no file (io/atomic_write.h).
class CacheWriter {
 public:
  /// \throw Error(Output) naming `path` when it cannot be created.
  CacheWriter(const std::string& path, const CacheHeader& header);

  const CacheHeader& header() const { return header_; }

  /// Writes sample `k` (3 x points floats, stored bit for bit). Safe to call from several threads.
  /// \throw Error(Numeric) for a coordinate that is not finite; Error(Output) when it cannot be
  ///        written.
  void write_sample(std::size_t k, const CacheSample& xyz);

  /// \throw Error(Internal) when a sample was not written; Error(Output) when the file cannot be
  ///        completed.
  void commit();

 private:
  std::string path_;
  CacheHeader header_;
  AtomicFile file_;
  std::mutex mutex_;
  std::vector<bool> written_;
};

}  // namespace skinslide
