// libFuzzer target: the MDD point cache reader (tests/fuzz/cache_fuzz.h says what is checked).

#include "cache_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return skinslide::fuzz::read_cache(skinslide::CacheFormat::Mdd, data, size);
}
