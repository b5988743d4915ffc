#include "core/cores.h"

#include <sched.h>

#include <algorithm>
#include <thread>

namespace skinslide {

unsigned usable_cores() {
  cpu_set_t mask;
  CPU_ZERO(&mask);
  // Fails only on machines with more CPUs than a cpu_set_t holds (1024).
  if (sched_getaffinity(0, sizeof mask, &mask) == 0) {
    const int count = CPU_COUNT(&mask);
    if (count > 0) return static_cast<unsigned>(count);
  }
  return std::max(1u, std::thread::hardware_concurrency());
}

}  // namespace skinslide
