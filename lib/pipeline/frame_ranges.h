// Farm frame ranges (`--frames 1-100:5,200`): which frames of a list a task slides.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace skinslide {

/// One term of a frame range list: first..last inclusive, every `step`-th frame from `first`.
struct FrameRange {
  long long first = 0;
  long long last = 0;
  long long step = 1;
};

/// Parses a frame range list as render farm schedulers pass it (OpenCue, Deadline): terms
/// separated by commas, each `N`, `A-B` (inclusive) or `A-B:S` / `A-BxS` (every S-th frame from
/// A). Frame numbers are non-negative integers; spaces around terms are allowed.
/// \throw Error(Usage) naming the term for anything else: an empty term, a range running
///        backwards, a step below 1, a number too large.
std::vector<FrameRange> parse_frame_ranges(const std::string& spec);

/// True when `frame` is one of the frames the ranges name.
bool in_frame_ranges(const std::vector<FrameRange>& ranges, long long frame);

/// The frame number of a frame file: the last run of digits in its file name before the
/// extension (`shot/arm.0042.obj` -> 42, `f7.obj` -> 7); nullopt when there is none or when
/// it does not fit in a long long.
std::optional<long long> frame_number(const std::string& path);

/// The sequence a frame file belongs to: its file name with the frame number (frame_number's
/// digits) as `#` (`shot/arm.0042.obj` -> `arm.#.obj`); nullopt when it has no frame number.
std::optional<std::string> frame_sequence(const std::string& path);

}  // namespace skinslide
