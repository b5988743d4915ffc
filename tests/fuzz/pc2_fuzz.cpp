// libFuzzer target: the PC2 point cache reader (tests/fuzz/cache_fuzz.h says what is checked).

#include "cache_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return skinslide::fuzz::read_cache(skinslide::CacheFormat::Pc2, data, size);
}
