// Locale-free number text: shortest round-trip doubles out, strict doubles and integers in.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace skinslide {

/// Shortest text that reads back to exactly `x` (std::to_chars), e.g. "0.1", "1e-05", "-3".
std::string format_double(double x);

/// Shortest text that reads back to exactly `x` as a float32 ("0.041666668", not the double's
/// "0.0416666679084301"): for the values of float32 files (point caches).
std::string format_float(float x);

/// The same text held in place, for loops that format every coordinate of a frame: most are
/// longer than a std::string keeps without allocating.
struct DoubleText {
  char chars[32];
  std::size_t size;
  std::string_view view() const { return {chars, size}; }
};
DoubleText double_text(double x);

/// "1 patch", "2 patches": a count and its noun, singular for exactly one.
std::string counted(std::size_t n, std::string_view one, std::string_view many);

/// Four significant digits ("%.4g"), for log lines: "0.1235", "1.5e-05".
std::string log_number(double x);

/// Parses the whole of `text` as a double ("1", "-2.5e3", "+1"); nullopt when it is not one.
/// "nan" and "inf" parse (the caller decides whether non-finite values are allowed). A number
/// beyond the largest double reads as an infinity ("1e999"), one nearer to 0 than the smallest
/// subnormal as a zero ("1e-400"), with their signs, as strtod reads them.
std::optional<double> parse_double(std::string_view text);

/// Parses the whole of `text` as a (possibly signed) integer; nullopt otherwise or on overflow.
std::optional<long long> parse_integer(std::string_view text);

}  // namespace skinslide
