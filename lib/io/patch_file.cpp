#include "io/patch_file.h"

#include <algorithm>
#include <string_view>

#include "core/error.h"
#include "io/atomic_write.h"
#include "core/number_format.h"
#include "io/token_lines.h"

namespace skinslide {
namespace {

// "12" -> id; nullopt if not a non-negative integer.
std::optional<long long> face_id(std::string_view t) {
  if (t.empty() || t.front() == '+' || t.front() == '-') return std::nullopt;
  return parse_integer(t);
}

// Parses "a" or "a<sep>b" into a range; nullopt when it is neither.
std::optional<std::pair<long long, long long>> id_or_range(std::string_view t, char sep) {
  const size_t s = t.find(sep, 1);
  if (s == std::string_view::npos) {
    const auto a = face_id(t);
    if (!a) return std::nullopt;
    return std::make_pair(*a, *a);
  }
  const auto a = face_id(t.substr(0, s));
  const auto b = face_id(t.substr(s + 1));
  if (!a || !b) return std::nullopt;
  return std::make_pair(*a, *b);
}

}  // namespace

PatchSelection parse_patch(const std::string& path, const std::string& text) {
  PatchSelection sel;
  sel.path = path;
  long object_line = 0;
  for_each_token_line(
      path, text, "a patch file", [&](long line, const std::vector<std::string_view>& tokens) {
        for (const std::string_view tok : tokens) {
          std::optional<std::pair<long long, long long>> range;
          const size_t bracket = tok.find("f[");
          if (bracket != std::string_view::npos && tok.back() == ']' &&
              (bracket == 0 || tok[bracket - 1] == '.')) {
            // Maya component string: [object.]f[a] or [object.]f[a:b]
            const std::string object(tok.substr(0, bracket == 0 ? 0 : bracket - 1));
            range = id_or_range(tok.substr(bracket + 2, tok.size() - bracket - 3), ':');
            if (range && !object.empty()) {
              if (sel.object.empty()) {
                sel.object = object;
                object_line = line;
              } else if (sel.object != object) {
                throw_input(path, line,
                            "names object '" + object + "' but line " +
                                std::to_string(object_line) + " names '" + sel.object +
                                "': one patch file selects faces of one mesh");
              }
            }
          } else {
            range = id_or_range(tok, '-');
          }
          if (!range)
            throw_input(path, line,
                        "unknown token " + quoted_token(tok) +
                            ": expected a face id (12), a range (12-40) or a Maya component "
                            "(pBody.f[12:40])");
          if (range->first > range->second)
            throw_input(path, line, "range " + quoted_token(tok) + " runs backwards");
          sel.ranges.push_back({range->first, range->second, line});
        }
      });
  return sel;
}

PatchSelection read_patch(const std::string& path) { return parse_patch(path, read_file(path)); }

std::vector<Index> selected_faces(const PatchSelection& selection, Index face_count) {
  std::vector<Index> faces;
  for (const FaceRange& r : selection.ranges) {
    if (r.last >= face_count)
      throw_input(selection.path, r.line,
                  "face " + std::to_string(r.last) + " is out of range (the bind has " +
                      std::to_string(face_count) + " faces, numbered 0 to " +
                      std::to_string(face_count - 1) + ")");
    for (long long f = r.first; f <= r.last; ++f) faces.push_back(static_cast<Index>(f));
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  if (faces.empty()) throw_input(selection.path, 0, "selects no faces");
  return faces;
}

}  // namespace skinslide
