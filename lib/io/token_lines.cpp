#include "io/token_lines.h"

namespace skinslide {

std::string quoted_token(std::string_view t) {
  constexpr size_t kMax = 40;
  std::string s(t.substr(0, kMax));
  if (t.size() > kMax) s += "...";
  return "'" + s + "'";
}

}  // namespace skinslide
