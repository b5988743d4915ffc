#include "core/number_format.h"

#include <charconv>
#include <cstdio>

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

std::optional<double> parse_double(std::string_view text) {
  // from_chars rejects a leading '+', which some exporters write.
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return std::nullopt;
  double x = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), x);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size()) return std::nullopt;
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

}  // namespace skinslide
