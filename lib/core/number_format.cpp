#include "core/number_format.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <limits>

namespace skinslide {

DoubleText double_text(double x) {
  DoubleText t;
  const auto r = std::to_chars(t.chars, t.chars + sizeof t.chars, x);
  t.size = static_cast<std::size_t>(r.ptr - t.chars);
  return t;
}

std::string format_double(double x) { return std::string(double_text(x).view()); }

std::string format_float(float x) {
  char chars[32];
  const auto r = std::to_chars(chars, chars + sizeof chars, x);
  return std::string(chars, r.ptr);
}

std::string log_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

namespace {

// The value of a decimal number that std::from_chars read whole but found out of range: zero
// when it is nearer to 0 than the smallest subnormal (1e-400), infinity when beyond the largest
// double (1e999), with its sign, as strtod reads them. Which one is told by the power of ten of
// its first significant digit: digits before the point, or minus the zeros after it, plus the
// exponent.
double out_of_range_value(std::string_view text) {
  const bool negative = text.front() == '-';
  if (negative) text.remove_prefix(1);
  const size_t e = std::min(text.find_first_of("eE"), text.size());
  long long magnitude = 0;
  bool significant = false, fraction = false;
  for (size_t i = 0; i < e; ++i) {
    if (text[i] == '.') {
      fraction = true;
    } else if (significant || text[i] != '0') {
      significant = true;
      if (!fraction) ++magnitude;
    } else if (fraction) {
      --magnitude;
    }
  }
  // The exponent saturates: any exponent this far from 0 decides the side on its own.
  constexpr long long kExponentCap = 1'000'000'000;
  long long exponent = 0;
  const bool negative_exponent = e + 1 < text.size() && text[e + 1] == '-';
  for (size_t i = e + 1; i < text.size(); ++i)
    if (text[i] >= '0' && text[i] <= '9')
      exponent = std::min(kExponentCap, exponent * 10 + (text[i] - '0'));
  magnitude += negative_exponent ? -exponent : exponent;
  const double x = magnitude > 0 ? std::numeric_limits<double>::infinity() : 0.0;
  return negative ? -x : x;
}

}  // namespace

std::optional<double> parse_double(std::string_view text) {
  // from_chars rejects a leading '+', which some exporters write.
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return std::nullopt;
  double x = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), x);
  if (r.ptr != text.data() + text.size()) return std::nullopt;
  if (r.ec == std::errc::result_out_of_range) return out_of_range_value(text);
  if (r.ec != std::errc()) return std::nullopt;
  return x;
}

std::optional<long long> parse_integer(std::string_view text) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return std::nullopt;
  long long x = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), x);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size()) return std::nullopt;
  return x;
}

std::string counted(std::size_t n, std::string_view one, std::string_view many) {
  return std::to_string(n) + " " + std::string(n == 1 ? one : many);
}

}  // namespace skinslide
