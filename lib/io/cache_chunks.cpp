#include "io/cache_chunks.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>

#include "core/check.h"
#include "core/error.h"
#include "io/atomic_write.h"
#include "core/number_format.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kFrameDigits = 4;  // shot.0001-0100.pc2, as frame files are numbered

std::string padded(long long frame) {
  const std::string digits = std::to_string(frame);
  return std::string(kFrameDigits > digits.size() ? kFrameDigits - digits.size() : 0, '0') + digits;
}

std::string frames_text(const ChunkName& n) {
  return "frames " + std::to_string(n.first) + "-" + std::to_string(n.last);
}

struct Chunk {
  std::string path;
  ChunkName name;
  std::unique_ptr<CacheReader> reader;
};

// Reads every chunk's header and name, sorted by first frame.
std::vector<Chunk> read_chunks(const std::vector<std::string>& paths) {
  std::vector<Chunk> chunks;
  for (const std::string& path : paths) {
    const std::optional<ChunkName> name = parse_chunk_name(path);
    if (!name)
      throw Error(ErrorKind::Input,
                  path +
                      ": not a chunk's name: expected <shot>.<first>-<last>.pc2 or .mdd, as "
                      "skinslide --frames names a chunk (shot.0101-0200.pc2)");
    chunks.push_back({path, *name, std::make_unique<CacheReader>(path)});
  }
  std::sort(chunks.begin(), chunks.end(),
            [](const Chunk& a, const Chunk& b) { return a.name.first < b.name.first; });
  return chunks;
}

[[noreturn]] void bad_chunk(const Chunk& c, const std::string& what) {
  throw Error(ErrorKind::Input, c.path + ": " + what);
}

// A chunk's name must tell its own frames: PC2 by its header's frame numbers, MDD (whose frame
// numbers are sample indices) by its sample count.
void check_name(const Chunk& c) {
  const CacheHeader& h = c.reader->header();
  const bool pc2 = h.format == CacheFormat::Pc2;
  const long long first = pc2 ? sample_frame(h, 0) : c.name.first;
  const long long last =
      pc2 ? sample_frame(h, static_cast<std::size_t>(h.samples) - 1) : first + h.samples - 1;
  if (first == c.name.first && last == c.name.last) return;
  bad_chunk(c, "its name says " + frames_text(c.name) + ", but its " + std::to_string(h.samples) +
                   " samples are frames " + std::to_string(first) + "-" + std::to_string(last) +
                   ": was it renamed?");
}

// `next` must follow `previous` with nothing between and nothing twice. `before` counts the
// samples of every chunk before `next`; `joined` is the first chunk's header.
void check_follows(const Chunk& previous, const Chunk& next, const CacheHeader& joined,
                   std::size_t before) {
  const CacheHeader& a = previous.reader->header();
  const CacheHeader& b = next.reader->header();
  if (next.name.stem != previous.name.stem || next.name.extension != previous.name.extension)
    bad_chunk(next, "is not a chunk of " + previous.name.stem + previous.name.extension);
  if (b.points != a.points)
    bad_chunk(next, "has " + std::to_string(b.points) + " points; " + previous.path + " has " +
                        std::to_string(a.points));
  if (next.name.first <= previous.name.last)
    bad_chunk(next, frames_text(next.name) + " overlap " + previous.path + "'s " +
                        frames_text(previous.name));
  if (b.format == CacheFormat::Mdd) {
    if (next.name.first != previous.name.last + 1)
      bad_chunk(next, "starts at frame " + std::to_string(next.name.first) +
                          " but the chunks before it end at frame " +
                          std::to_string(previous.name.last) + ": the frames between are missing");
    if (!(b.times.front() > a.times.back()))
      bad_chunk(next, "its first time (" + format_float(b.times.front()) +
                          " s) is not after the last of " + previous.path + " (" +
                          format_float(a.times.back()) + " s)");
    return;
  }
  if (b.sample_rate != a.sample_rate)
    bad_chunk(next, "sampleRate " + format_float(b.sample_rate) + "; " + previous.path + " has " +
                        format_float(a.sample_rate));
  // Half a sample apart at most: a chunk's startFrame is rounded to float32 from its own first
  // sample's frame, so it may differ from the one counted from the first chunk in its last bits.
  const double expected = double(joined.start_frame) + double(before) * double(a.sample_rate);
  if (std::abs(double(b.start_frame) - expected) > 0.5 * double(a.sample_rate))
    bad_chunk(next, "starts at frame " + format_float(b.start_frame) +
                        " but the chunks before it end one sample before frame " +
                        format_double(expected) + ": the samples between are missing");
}

}  // namespace

CacheHeader chunk_header(const CacheHeader& whole, std::size_t first, std::size_t count) {
  SKINSLIDE_CHECK(count > 0 && first + count <= static_cast<std::size_t>(whole.samples),
                  "a chunk inside the cache");
  CacheHeader h = whole;
  h.samples = static_cast<std::int32_t>(count);
  if (whole.format == CacheFormat::Pc2) {
    if (first > 0)
      h.start_frame =
          static_cast<float>(double(whole.start_frame) + double(first) * double(whole.sample_rate));
  } else {
    h.times.assign(whole.times.begin() + static_cast<std::ptrdiff_t>(first),
                   whole.times.begin() + static_cast<std::ptrdiff_t>(first + count));
  }
  return h;
}

std::string chunk_file_name(const std::string& stem, long long first, long long last,
                            const std::string& extension) {
  return stem + "." + padded(first) + "-" + padded(last) + extension;
}

std::optional<ChunkName> parse_chunk_name(const std::string& path) {
  const fs::path p(path);
  ChunkName n;
  n.extension = p.extension().string();
  const std::string rest = p.stem().string();  // "shot.0101-0200"
  const std::size_t dot = rest.rfind('.');
  if (dot == std::string::npos || dot == 0) return std::nullopt;
  const std::string range = rest.substr(dot + 1);
  const std::size_t dash = range.find('-');
  if (dash == std::string::npos || dash == 0 || dash + 1 == range.size()) return std::nullopt;
  const auto digits_only = [](const std::string& s) {
    return std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  const std::string a = range.substr(0, dash), b = range.substr(dash + 1);
  if (!digits_only(a) || !digits_only(b)) return std::nullopt;
  const auto first = parse_integer(a), last = parse_integer(b);
  if (!first || !last || *first > *last) return std::nullopt;
  n.stem = rest.substr(0, dot);
  n.first = *first;
  n.last = *last;
  return n;
}

JoinResult join_cache_chunks(const std::vector<std::string>& paths, const std::string& output_dir) {
  if (paths.empty()) throw Error(ErrorKind::Usage, "join: no chunks given");
  const std::vector<Chunk> chunks = read_chunks(paths);
  CacheHeader joined = chunks.front().reader->header();
  check_name(chunks.front());
  std::size_t total = static_cast<std::size_t>(joined.samples);
  for (std::size_t i = 1; i < chunks.size(); ++i) {
    check_name(chunks[i]);
    check_follows(chunks[i - 1], chunks[i], joined, total);
    const CacheHeader& h = chunks[i].reader->header();
    if (joined.format == CacheFormat::Mdd)
      joined.times.insert(joined.times.end(), h.times.begin(), h.times.end());
    total += static_cast<std::size_t>(h.samples);
    if (total > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
      bad_chunk(chunks[i], "the chunks hold more samples than a cache can count (2^31 - 1)");
  }
  joined.samples = static_cast<std::int32_t>(total);
  JoinResult result;
  result.header = joined;
  result.chunks = chunks.size();
  const ChunkName& name = chunks.front().name;
  result.output = (fs::path(output_dir) / (name.stem + name.extension)).string();
  // The output's name has no frame range: it is never a chunk's (and a link of that name to a
  // chunk is replaced by the rename, the chunk kept).
  std::error_code ec;
  if (!output_dir.empty()) {
    fs::create_directories(output_dir, ec);
    if (ec || !fs::is_directory(output_dir))
      throw Error(ErrorKind::Output,
                  output_dir + ": cannot create the output folder" +
                      (ec ? ": " + ec.message() : std::string(": exists and is not a folder")));
  }
  CacheWriter writer(result.output, joined);
  std::size_t k = 0;
  for (const Chunk& c : chunks)
    for (std::size_t j = 0; j < static_cast<std::size_t>(c.reader->header().samples); ++j)
      writer.write_sample(k++, c.reader->sample(j));
  writer.commit();
  sync_folder(output_dir.empty() ? "." : output_dir);
  return result;
}

}  // namespace skinslide
