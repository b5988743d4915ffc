// Wall time of a stage, for the report's timings and the progress line. Never part of an output:
// the outputs do not depend on how long anything took.
#pragma once

#include <chrono>

namespace skinslide {

using Clock = std::chrono::steady_clock;

/// Seconds from `start` to now.
inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace skinslide
