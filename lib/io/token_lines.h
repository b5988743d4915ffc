// The line syntax shared by skinslide's list files (patch files, vertex lists, weight files):
// tokens separated by whitespace or commas, `#` to the end of a line is a comment, and a NUL
// byte means the file is not text.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace skinslide {

/// Whitespace (but not a newline) or a comma.
inline bool is_list_separator(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f' || c == ',';
}

/// `t` in single quotes for a message, cut to 40 characters.
std::string quoted_token(std::string_view t);

/// Calls f(line number, tokens) for every line of `text` (1-based; comments stripped; tokens may
/// be empty; a leading UTF-8 byte-order mark skipped). `kind` names the file in the NUL-byte error,
/// e.g. "a patch file". \throw Error(Input) "path:line: binary data (NUL byte): not KIND"; whatever
/// f throws.
template <typename F>
void for_each_token_line(const std::string& path, const std::string& text, const char* kind,
                         F&& f) {
  long line = 0;
  // A UTF-8 byte-order mark (some Windows tools write one) is not part of the first token.
  size_t pos = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  std::vector<std::string_view> tokens;
  while (pos < text.size()) {
    ++line;
    size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) eol = text.size();
    std::string_view body(text.data() + pos, eol - pos);
    pos = eol + 1;
    if (body.find('\0') != std::string_view::npos)
      throw_input(path, line, std::string("binary data (NUL byte): not ") + kind);
    body = body.substr(0, body.find('#'));
    tokens.clear();
    size_t i = 0;
    while (i < body.size()) {
      while (i < body.size() && is_list_separator(body[i])) ++i;
      if (i >= body.size()) break;
      const size_t s = i;
      while (i < body.size() && !is_list_separator(body[i])) ++i;
      tokens.push_back(body.substr(s, i - s));
    }
    f(line, tokens);
  }
}

}  // namespace skinslide
