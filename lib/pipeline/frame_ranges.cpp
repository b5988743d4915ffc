#include "pipeline/frame_ranges.h"

#include <cctype>
#include <charconv>
#include <filesystem>
#include <string_view>
#include <utility>

#include "core/error.h"

namespace skinslide {
namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// A whole run of digits as a number; nullopt for anything else (signs included) or overflow.
std::optional<long long> number(std::string_view s) {
  if (s.empty()) return std::nullopt;
  for (char c : s)
    if (!is_digit(c)) return std::nullopt;
  long long x = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), x);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return std::nullopt;
  return x;
}

[[noreturn]] void bad_term(std::string_view term, const std::string& what) {
  throw Error(ErrorKind::Usage, "--frames: '" + std::string(term) + "' " + what +
                                    "; expected frame numbers like 1-100, 1-100:5 or 3,7,12-20");
}

FrameRange parse_term(std::string_view term) {
  if (term.empty()) bad_term(term, "is empty");
  FrameRange r;
  std::string_view range = term;
  const size_t step_at = term.find_first_of(":x");
  if (step_at != std::string_view::npos) {
    range = term.substr(0, step_at);
    const auto step = number(term.substr(step_at + 1));
    if (!step) bad_term(term, "has no step after '" + std::string(1, term[step_at]) + "'");
    if (*step < 1) bad_term(term, "has a step below 1");
    r.step = *step;
  }
  const size_t dash = range.find('-');
  if (dash == std::string_view::npos) {
    const auto n = number(range);
    if (!n) bad_term(term, "is not a frame number or range");
    if (step_at != std::string_view::npos) bad_term(term, "has a step but no range");
    r.first = r.last = *n;
    return r;
  }
  const auto a = number(range.substr(0, dash));
  const auto b = number(range.substr(dash + 1));
  if (!a || !b) bad_term(term, "is not a frame number or range");
  if (*a > *b) bad_term(term, "runs backwards");
  r.first = *a;
  r.last = *b;
  return r;
}

}  // namespace

std::vector<FrameRange> parse_frame_ranges(const std::string& spec) {
  std::vector<FrameRange> ranges;
  std::string_view rest(spec);
  while (true) {
    const size_t comma = rest.find(',');
    ranges.push_back(parse_term(trimmed(rest.substr(0, comma))));
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return ranges;
}

bool in_frame_ranges(const std::vector<FrameRange>& ranges, long long frame) {
  for (const FrameRange& r : ranges)
    if (frame >= r.first && frame <= r.last && (frame - r.first) % r.step == 0) return true;
  return false;
}

namespace {

// Where the frame number's digits are in `stem`: [begin, end); empty when it has none.
std::pair<size_t, size_t> frame_digits(const std::string& stem) {
  size_t end = stem.size();
  while (end > 0 && !is_digit(stem[end - 1])) --end;
  size_t begin = end;
  while (begin > 0 && is_digit(stem[begin - 1])) --begin;
  return {begin, end};
}

}  // namespace

std::optional<long long> frame_number(const std::string& path) {
  const std::string stem = std::filesystem::path(path).stem().string();
  const auto [begin, end] = frame_digits(stem);
  return number(std::string_view(stem).substr(begin, end - begin));
}

std::optional<std::string> frame_sequence(const std::string& path) {
  if (!frame_number(path)) return std::nullopt;
  const std::filesystem::path p(path);
  const std::string stem = p.stem().string();
  const auto [begin, end] = frame_digits(stem);
  return stem.substr(0, begin) + "#" + stem.substr(end) + p.extension().string();
}

}  // namespace skinslide
