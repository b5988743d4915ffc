// The body of the point cache fuzz targets (pc2_fuzz.cpp, mdd_fuzz.cpp): any input is read or
// refused as bad input (never an internal error, a crash or an allocation past the input's size);
// a cache that reads is exactly the size its header says, its header and every sample encode
// back to the input's bytes, its frame numbers increase, and its chunks' headers read back.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>

#include "core/error.h"
#include "io/cache_chunks.h"
#include "io/point_cache.h"

namespace skinslide::fuzz {

inline void require(bool cond) {
  if (!cond) std::abort();
}

inline int read_cache(CacheFormat format, const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  std::unique_ptr<CacheReader> reader;
  try {
    reader = std::make_unique<CacheReader>("fuzz", format, bytes);
  } catch (const Error& e) {
    require(e.kind() == ErrorKind::Input);
    return 0;
  }
  const CacheHeader& h = reader->header();
  require(h.samples > 0 && h.points > 0);
  require(cache_bytes(h) == bytes.size());
  require(encode_header(h) == bytes.substr(0, header_bytes(h)));
  const std::size_t samples = static_cast<std::size_t>(h.samples);
  for (std::size_t k = 0; k < samples; ++k) {
    if (k > 0) require(sample_frame(h, k) >= sample_frame(h, k - 1));
    try {
      const CacheSample xyz = reader->sample(k);
      require(xyz.size() == 3 * static_cast<std::size_t>(h.points));
      const std::string stored = encode_sample("fuzz", format, k, xyz);
      require(stored == bytes.substr(sample_offset(h, k), stored.size()));
    } catch (const Error& e) {
      require(e.kind() == ErrorKind::Input);  // a NaN or an infinity, named
    }
  }
  // A chunk's header (the tail from the middle sample) is a valid header of its own.
  const CacheHeader tail = chunk_header(h, samples / 2, samples - samples / 2);
  const std::string encoded = encode_header(tail);
  const CacheHeader back = parse_cache_header("fuzz", format, encoded, cache_bytes(tail));
  require(back.samples == tail.samples && back.points == h.points && back.times == tail.times);
  return 0;
}

}  // namespace skinslide::fuzz
