// JSON text that every report writes the same way: `skinslide --report` (pipeline/report.cpp) and
// `skinslide compare --report` (compare/compare_report.cpp).
#pragma once

#include <string>

namespace skinslide {

/// `s` as a JSON string, quotes included: `"` and `\` escaped, newline and tab as `\n` and `\t`,
/// any other control character as `\u00XX`; well-formed UTF-8 as it is, and each byte that is
/// not part of it (a file name in another encoding) as U+FFFD, so the text stays valid JSON.
std::string json_string(const std::string& s);

}  // namespace skinslide
