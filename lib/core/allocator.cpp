#include "core/allocator.h"

#include <malloc.h>

namespace skinslide {

bool keep_freed_memory() {
  constexpr int kHuge = 1 << 30;  // bytes: above any block a frame of a 1M-vertex patch needs
  const bool mapped = mallopt(M_MMAP_THRESHOLD, kHuge) == 1;
  const bool trimmed = mallopt(M_TRIM_THRESHOLD, kHuge) == 1;
  const bool one_arena = mallopt(M_ARENA_MAX, 1) == 1;
  return mapped && trimmed && one_arena;
}

}  // namespace skinslide
