#include "core/allocator.h"

#include <malloc.h>

namespace skinslide {

bool keep_freed_memory() {
  constexpr int kHuge = 1 << 30;
  const bool mapped = mallopt(M_MMAP_THRESHOLD, kHuge) == 1;
  const bool trimmed = mallopt(M_TRIM_THRESHOLD, kHuge) == 1;
  return mapped && trimmed;
}

}  // namespace skinslide
