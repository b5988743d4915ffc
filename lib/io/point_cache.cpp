#include "io/point_cache.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/check.h"
#include "core/error.h"
#include "core/file_extension.h"
#include "core/number_format.h"
#include "io/run_inputs.h"

namespace skinslide {
namespace {

constexpr char kPc2Magic[12] = {'P', 'O', 'I', 'N', 'T', 'C', 'A', 'C', 'H', 'E', '2', '\0'};
constexpr std::int32_t kPc2Version = 1;  // the only one there is
// PC2 field offsets (bytes from the start of the file).
constexpr std::uint64_t kPc2VersionAt = 12, kPc2PointsAt = 16, kPc2StartAt = 20, kPc2RateAt = 24,
                        kPc2SamplesAt = 28;
// MDD field offsets.
constexpr std::uint64_t kMddSamplesAt = 0, kMddPointsAt = 4, kMddTimesAt = 8;
// A whole frame within this of a PC2 sample's frame number is that sample's frame (Blender's
// FRAME_SNAP_EPS in MOD_meshcache_util): rates such as 0.01 are not exact in float32.
constexpr double kFrameSnap = 1e-4;
// Frame numbers beyond this are refused: they must stay whole numbers exactly in a double.
constexpr double kLargestFrame = 1e15;

bool big_endian(CacheFormat format) { return format == CacheFormat::Mdd; }

std::uint32_t load_u32(const char* p, bool big) {
  const auto b = [&](int i) {
    return static_cast<std::uint32_t>(static_cast<unsigned char>(p[i]));
  };
  return big ? (b(0) << 24) | (b(1) << 16) | (b(2) << 8) | b(3)
             : b(0) | (b(1) << 8) | (b(2) << 16) | (b(3) << 24);
}

void store_u32(char* p, std::uint32_t v, bool big) {
  for (int i = 0; i < 4; ++i) {
    const int shift = big ? 8 * (3 - i) : 8 * i;
    p[i] = static_cast<char>((v >> shift) & 0xffu);
  }
}

std::int32_t load_i32(std::string_view head, std::uint64_t at, bool big) {
  return static_cast<std::int32_t>(load_u32(head.data() + at, big));
}

float load_f32(std::string_view head, std::uint64_t at, bool big) {
  return std::bit_cast<float>(load_u32(head.data() + at, big));
}

[[noreturn]] void bad(const std::string& path, const std::string& what) {
  throw Error(ErrorKind::Input, path + ": " + what);
}

std::string byte_at(std::uint64_t offset) { return "byte " + std::to_string(offset) + ": "; }

std::string number(float x) { return format_float(x); }

// The counts' checks shared by both formats: at least one point and one sample.
void check_counts(const std::string& path, std::int32_t points, std::uint64_t points_at,
                  std::int32_t samples, std::uint64_t samples_at) {
  if (samples == 0)
    bad(path, byte_at(samples_at) + "the sample count is 0: the cache holds no samples");
  if (samples < 0)
    bad(path, byte_at(samples_at) + "the sample count is " + std::to_string(samples) +
                  ": it cannot be negative");
  if (points <= 0)
    bad(path, byte_at(points_at) + "the point count is " + std::to_string(points) +
                  ": a cache needs at least one point");
}

// The file must hold exactly the header and `samples` samples of `points` points. Division, not
// multiplication: the counts come from the file and their product may overflow.
void check_size(const std::string& path, std::uint64_t header, std::int32_t points,
                std::int32_t samples, std::uint64_t file_size) {
  const std::string counts = "the header says " + std::to_string(samples) + " samples of " +
                             std::to_string(points) + " points";
  if (file_size < header)
    bad(path, "truncated: " + counts + ", whose header alone is " + std::to_string(header) +
                  " bytes; the file has " + std::to_string(file_size));
  const std::uint64_t per_sample = kBytesPerPoint * static_cast<std::uint64_t>(points);
  const std::uint64_t whole = (file_size - header) / per_sample;
  const std::uint64_t rest = (file_size - header) % per_sample;
  if (whole < static_cast<std::uint64_t>(samples))
    bad(path, "truncated: " + counts + "; the file has " + std::to_string(file_size) +
                  " bytes, which hold " + std::to_string(whole) + " of them" +
                  (rest ? " (sample " + std::to_string(whole) + " is cut at byte " +
                              std::to_string(file_size) + ")"
                        : std::string()));
  if (whole > static_cast<std::uint64_t>(samples) || rest != 0) {
    const std::uint64_t expected = header + per_sample * static_cast<std::uint64_t>(samples);
    bad(path, counts + " (" + std::to_string(expected) + " bytes); the file has " +
                  std::to_string(file_size) + ": " + std::to_string(file_size - expected) +
                  " bytes past the last sample");
  }
}

CacheHeader parse_pc2(const std::string& path, std::string_view head, std::uint64_t file_size) {
  if (file_size == 0) bad(path, "the file is empty (0 bytes)");
  if (file_size < kPc2HeaderBytes || head.size() < kPc2HeaderBytes)
    bad(path, "truncated: a PC2 header is 32 bytes; the file has " + std::to_string(file_size));
  if (std::memcmp(head.data(), kPc2Magic, sizeof kPc2Magic) != 0)
    bad(path, "not a PC2 point cache: it does not start with \"POINTCACHE2\\0\"");
  CacheHeader h;
  h.format = CacheFormat::Pc2;
  const std::int32_t version = load_i32(head, kPc2VersionAt, false);
  if (version != kPc2Version)
    bad(path, byte_at(kPc2VersionAt) + "PC2 version " + std::to_string(version) +
                  "; only version 1 exists");
  h.points = load_i32(head, kPc2PointsAt, false);
  h.start_frame = load_f32(head, kPc2StartAt, false);
  h.sample_rate = load_f32(head, kPc2RateAt, false);
  h.samples = load_i32(head, kPc2SamplesAt, false);
  check_counts(path, h.points, kPc2PointsAt, h.samples, kPc2SamplesAt);
  if (!std::isfinite(h.start_frame) || std::abs(h.start_frame) > kLargestFrame)
    bad(path, byte_at(kPc2StartAt) + "startFrame " + number(h.start_frame) +
                  " is not a finite frame number");
  if (!std::isfinite(h.sample_rate) || !(h.sample_rate > 0))
    bad(path, byte_at(kPc2RateAt) + "sampleRate " + number(h.sample_rate) +
                  ": the frames from one sample to the next must be a finite number above 0");
  const double last = double(h.start_frame) + double(h.samples - 1) * double(h.sample_rate);
  if (std::abs(last) > kLargestFrame)
    bad(path, byte_at(kPc2RateAt) + "the last sample's frame number (" + format_double(last) +
                  ") is out of range");
  check_size(path, kPc2HeaderBytes, h.points, h.samples, file_size);
  return h;
}

CacheHeader parse_mdd(const std::string& path, std::string_view head, std::uint64_t file_size) {
  if (file_size == 0) bad(path, "the file is empty (0 bytes)");
  if (file_size < kMddCountBytes || head.size() < kMddCountBytes)
    bad(path, "truncated: an MDD file starts with two 4-byte counts; the file has " +
                  std::to_string(file_size) + " bytes");
  CacheHeader h;
  h.format = CacheFormat::Mdd;
  h.samples = load_i32(head, kMddSamplesAt, true);
  h.points = load_i32(head, kMddPointsAt, true);
  check_counts(path, h.points, kMddPointsAt, h.samples, kMddSamplesAt);
  const std::uint64_t header = header_bytes(h);
  check_size(path, header, h.points, h.samples, file_size);
  SKINSLIDE_CHECK(head.size() >= header, "the MDD times were read");
  h.times.resize(static_cast<std::size_t>(h.samples));
  for (std::size_t k = 0; k < h.times.size(); ++k) {
    const std::uint64_t at = kMddTimesAt + 4 * k;
    const float t = load_f32(head, at, true);
    if (!std::isfinite(t))
      bad(path, byte_at(at) + "the time of sample " + std::to_string(k) + " is " + number(t));
    if (k > 0 && !(t > h.times[k - 1]))
      bad(path, byte_at(at) + "the time of sample " + std::to_string(k) + " (" + number(t) +
                    " s) is not after sample " + std::to_string(k - 1) + "'s (" +
                    number(h.times[k - 1]) + " s): MDD times must increase");
    h.times[k] = t;
  }
  return h;
}

}  // namespace

std::optional<CacheFormat> cache_format(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".pc2") return CacheFormat::Pc2;
  if (ext == ".mdd") return CacheFormat::Mdd;
  return std::nullopt;
}

const char* to_string(CacheFormat format) { return format == CacheFormat::Pc2 ? "pc2" : "mdd"; }

std::uint64_t header_bytes(const CacheHeader& h) {
  return h.format == CacheFormat::Pc2
             ? kPc2HeaderBytes
             : kMddCountBytes + 4 * static_cast<std::uint64_t>(std::max(h.samples, 0));
}

std::uint64_t sample_offset(const CacheHeader& h, std::size_t k) {
  return header_bytes(h) + kBytesPerPoint * static_cast<std::uint64_t>(h.points) * k;
}

std::uint64_t cache_bytes(const CacheHeader& h) {
  return sample_offset(h, static_cast<std::size_t>(h.samples));
}

std::string encode_header(const CacheHeader& h) {
  std::string out(header_bytes(h), '\0');
  const bool big = big_endian(h.format);
  char* p = out.data();
  if (h.format == CacheFormat::Pc2) {
    std::memcpy(p, kPc2Magic, sizeof kPc2Magic);
    store_u32(p + kPc2VersionAt, static_cast<std::uint32_t>(kPc2Version), big);
    store_u32(p + kPc2PointsAt, static_cast<std::uint32_t>(h.points), big);
    store_u32(p + kPc2StartAt, std::bit_cast<std::uint32_t>(h.start_frame), big);
    store_u32(p + kPc2RateAt, std::bit_cast<std::uint32_t>(h.sample_rate), big);
    store_u32(p + kPc2SamplesAt, static_cast<std::uint32_t>(h.samples), big);
    return out;
  }
  SKINSLIDE_CHECK(h.times.size() == static_cast<std::size_t>(h.samples), "one time a sample");
  store_u32(p + kMddSamplesAt, static_cast<std::uint32_t>(h.samples), big);
  store_u32(p + kMddPointsAt, static_cast<std::uint32_t>(h.points), big);
  for (std::size_t k = 0; k < h.times.size(); ++k)
    store_u32(p + kMddTimesAt + 4 * k, std::bit_cast<std::uint32_t>(h.times[k]), big);
  return out;
}

Positions3 sample_positions(const CacheSample& sample) {
  Positions3 p(sample.size() / 3);
  for (std::size_t v = 0; v < p.size(); ++v)
    p[v] = Vec3(sample[3 * v], sample[3 * v + 1], sample[3 * v + 2]);
  return p;
}

std::string encode_sample(const std::string& path, CacheFormat format, std::size_t k,
                          const CacheSample& xyz) {
  const bool big = big_endian(format);
  std::string raw(4 * xyz.size(), '\0');
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    if (!std::isfinite(xyz[i]))
      throw Error(ErrorKind::Numeric, path + ": sample " + std::to_string(k) + ", point " +
                                          std::to_string(i / 3) + ": a coordinate is not finite");
    store_u32(raw.data() + 4 * i, std::bit_cast<std::uint32_t>(xyz[i]), big);
  }
  return raw;
}

long long sample_frame(const CacheHeader& h, std::size_t k) {
  if (h.format == CacheFormat::Mdd) return static_cast<long long>(k);
  const double frame = double(h.start_frame) + double(k) * double(h.sample_rate);
  const double nearest = std::round(frame);
  return static_cast<long long>(std::abs(frame - nearest) <= kFrameSnap ? nearest
                                                                        : std::floor(frame));
}

CacheHeader parse_cache_header(const std::string& path, CacheFormat format, std::string_view head,
                               std::uint64_t file_size) {
  return format == CacheFormat::Pc2 ? parse_pc2(path, head, file_size)
                                    : parse_mdd(path, head, file_size);
}

// ---- CacheReader -----------------------------------------------------------------------------

CacheReader::CacheReader(const std::string& path) : path_(path) {
  const std::optional<CacheFormat> format = cache_format(path);
  if (!format)
    throw Error(ErrorKind::Usage, path + ": not a point cache name (expected .pc2 or .mdd)");
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) bad(path, "cannot read: it is a directory");
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) bad(path, std::string("cannot read: ") + std::strerror(errno));
  note_input(path);
  try {
    header_ = read_header(*format);
  } catch (...) {
    ::close(fd_);  // the destructor does not run for a constructor that throws
    throw;
  }
}

CacheHeader CacheReader::read_header(CacheFormat format) const {
  struct stat st {};
  if (::fstat(fd_, &st) != 0) bad(path_, std::string("cannot read: ") + std::strerror(errno));
  const auto size = static_cast<std::uint64_t>(st.st_size);
  // The fixed part first; MDD's times only once its counts are known to fit in the file, so a
  // count read from a damaged file never sizes an allocation beyond the file itself.
  std::string head(std::min(size, kPc2HeaderBytes), '\0');
  read_at(0, head.data(), head.size());
  if (format == CacheFormat::Mdd && head.size() >= kMddCountBytes) {
    const std::int32_t samples = load_i32(head, kMddSamplesAt, true);
    const std::uint64_t times_end = kMddCountBytes + 4 * static_cast<std::uint64_t>(samples);
    if (samples > 0 && times_end <= size) {
      head.resize(times_end);
      read_at(0, head.data(), head.size());
    }
  }
  return parse_cache_header(path_, format, head, size);
}

CacheReader::CacheReader(const std::string& path, CacheFormat format, std::string bytes)
    : path_(path), bytes_(std::move(bytes)) {
  header_ = parse_cache_header(path, format, bytes_, bytes_.size());
}

CacheReader::~CacheReader() {
  if (fd_ >= 0) ::close(fd_);
}

void CacheReader::read_at(std::uint64_t offset, char* out, std::size_t size) const {
  if (fd_ < 0) {
    SKINSLIDE_CHECK(offset + size <= bytes_.size(), "a read inside the cache");
    std::memcpy(out, bytes_.data() + offset, size);
    return;
  }
  while (size > 0) {
    const ssize_t n = ::pread(fd_, out, size, static_cast<off_t>(offset));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) bad(path_, byte_at(offset) + "read failed: " + std::strerror(errno));
    if (n == 0) bad(path_, byte_at(offset) + "the file ended early: it shrank while being read");
    out += n;
    offset += static_cast<std::uint64_t>(n);
    size -= static_cast<std::size_t>(n);
  }
}

CacheSample CacheReader::sample(std::size_t k) const {
  SKINSLIDE_CHECK(k < static_cast<std::size_t>(header_.samples), "a sample of the cache");
  const std::size_t count = 3 * static_cast<std::size_t>(header_.points);
  std::string raw(4 * count, '\0');
  const std::uint64_t start = sample_offset(header_, k);
  read_at(start, raw.data(), raw.size());
  const bool big = big_endian(header_.format);
  CacheSample xyz(count);
  for (std::size_t i = 0; i < count; ++i) {
    xyz[i] = std::bit_cast<float>(load_u32(raw.data() + 4 * i, big));
    if (!std::isfinite(xyz[i]))
      bad(path_, byte_at(start + 4 * i) + "sample " + std::to_string(k) + ", point " +
                     std::to_string(i / 3) + ": coordinate " + "xyz"[i % 3] + " is " +
                     (std::isnan(xyz[i]) ? "NaN" : "infinite"));
  }
  return xyz;
}

// ---- CacheWriter -----------------------------------------------------------------------------

CacheWriter::CacheWriter(const std::string& path, const CacheHeader& header)
    : path_(path),
      header_(header),
      file_(path),
      written_(static_cast<std::size_t>(header.samples), false) {
  SKINSLIDE_CHECK(header.samples > 0 && header.points > 0, "a cache of at least one sample");
  file_.write_at(0, encode_header(header_));
}

void CacheWriter::write_sample(std::size_t k, const CacheSample& xyz) {
  SKINSLIDE_CHECK(k < written_.size(), "a sample of the cache");
  SKINSLIDE_CHECK(xyz.size() == 3 * static_cast<std::size_t>(header_.points), "one x y z a point");
  const std::string raw = encode_sample(path_, header_.format, k, xyz);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    SKINSLIDE_CHECK(!written_[k], "each sample written once");
    written_[k] = true;
  }
  file_.write_at(sample_offset(header_, k), raw);
}

void CacheWriter::commit() {
  const auto missing = std::find(written_.begin(), written_.end(), false);
  SKINSLIDE_CHECK(missing == written_.end(), "sample " +
                                                 std::to_string(missing - written_.begin()) +
                                                 " of " + path_ + " was never written");
  file_.commit();
}

}  // namespace skinslide
