#include "io/obj_read.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string_view>

#include "core/error.h"
#include "io/atomic_write.h"
#include "core/number_format.h"

namespace skinslide {
namespace {

// Per byte: 1 for a space, 2 for '#' (a token's end either way), 0 otherwise. The tokenizer
// visits every byte of the file; a table lookup is one load where the tests were five compares.
constexpr std::array<std::uint8_t, 256> kByteClass = [] {
  std::array<std::uint8_t, 256> c{};
  for (char s : {' ', '\t', '\r', '\v', '\f'}) c[static_cast<unsigned char>(s)] = 1;
  c['#'] = 2;
  return c;
}();

bool is_space(char c) { return kByteClass[static_cast<unsigned char>(c)] == 1; }

struct Token {
  std::string_view text;
  std::uint64_t begin;  // byte offset in the file
};

// Splits [begin, end) of `bytes` into whitespace-separated tokens, stopping at '#'.
void tokenize(const std::string& bytes, size_t begin, size_t end, std::vector<Token>& out) {
  out.clear();
  size_t i = begin;
  while (i < end) {
    while (i < end && is_space(bytes[i])) ++i;
    if (i >= end || bytes[i] == '#') break;
    const size_t s = i;
    while (i < end && kByteClass[static_cast<unsigned char>(bytes[i])] == 0) ++i;
    out.push_back({std::string_view(bytes.data() + s, i - s), s});
  }
}

std::string count_of(size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// True when faces[] names a vertex twice; `dup` gets the smallest such (0-based) vertex. A face
// of a few corners compares every pair; sorting a copy keeps a face line with thousands of
// entries linear-logarithmic.
bool repeated_vertex(const std::vector<Index>& face, std::vector<Index>& scratch, Index& dup) {
  if (face.size() <= 8) {
    bool found = false;
    for (size_t i = 0; i < face.size(); ++i)
      for (size_t j = i + 1; j < face.size(); ++j)
        if (face[i] == face[j] && (!found || face[i] < dup)) {
          dup = face[i];
          found = true;
        }
    return found;
  }
  scratch.assign(face.begin(), face.end());
  std::sort(scratch.begin(), scratch.end());
  const auto it = std::adjacent_find(scratch.begin(), scratch.end());
  if (it == scratch.end()) return false;
  dup = *it;
  return true;
}

// A statement that was meant as a vertex or a face but is not spelled as one: skipped as an
// unknown statement, it would shift every later vertex index (a face would then join the wrong
// vertices, and no error would say so). OBJ keywords are lower case and end at a space.
bool misspelt_vertex_or_face(std::string_view key) {
  if (key.empty()) return false;
  const char first = static_cast<char>(std::tolower(static_cast<unsigned char>(key[0])));
  if (first != 'v' && first != 'f') return false;
  std::string lower(key);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower != key &&
      (lower == "v" || lower == "f" || lower == "vt" || lower == "vn" || lower == "vp"))
    return true;  // `V`, `F`, `VN`, ...
  const char second = key.size() > 1 ? key[1] : ' ';
  return std::isdigit(static_cast<unsigned char>(second)) || second == '-' || second == '+' ||
         second == '.';  // `v1.0 2 3`: no space after the keyword
}

std::string quoted(std::string_view t) {
  constexpr size_t kMax = 40;
  std::string s(t.substr(0, kMax));
  if (t.size() > kMax) s += "...";
  return "'" + s + "'";
}

// True for the text of a number too large for a double ("1e999"), not an "inf" or "nan".
bool overflows(std::string_view t) {
  return std::any_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// A face corner is v, v/vt, v//vn or v/vt/vn: at most two slashes.
constexpr std::ptrdiff_t kMaxCornerSlashes = 2;

// Whether `text` is a whole number as written (a sign, then digits): one parse_integer refuses
// only when it is beyond a long long.
bool whole_number_text(std::string_view text) {
  const std::string_view digits = text.substr(!text.empty() && (text[0] == '+' || text[0] == '-'));
  return !digits.empty() && digits.find_first_not_of("0123456789") == std::string_view::npos;
}

// A corner's texture and normal parts (after its first and second '/'): each empty (`1//3`), or a
// whole number but 0, negative = relative. They are not read (vt and vn lines are kept as text),
// so they need not name an existing vt or vn; but a part that is no index (`1/x/1`, `1/0.5`) is
// not a corner as OBJ writes one: a corrupt export, or words joined to a face line.
template <typename Fail>
void check_corner_parts(std::string_view entry, Fail&& fail) {
  size_t slash = entry.find('/');
  for (const char* part_name : {"texture", "normal"}) {
    if (slash == std::string_view::npos) return;
    const size_t next = entry.find('/', slash + 1);
    const std::string_view part =
        entry.substr(slash + 1, next == std::string_view::npos ? next : next - slash - 1);
    slash = next;
    if (part.empty()) continue;
    const auto idx = parse_integer(part);
    if (idx && *idx != 0) continue;
    const std::string what = "face corner " + quoted(entry) + ": " + part_name + " index ";
    if (idx) fail(what + "0 (OBJ indices start at 1)");
    fail(what + quoted(part) +
         (whole_number_text(part) ? " is too large" : " is not a whole number") +
         " (a corner is v, v/vt, v//vn or v/vt/vn, each a whole number)");
  }
}

// Numbers a `v` line may hold after x y z: w (OBJ's optional weight), or a colour r g b or
// r g b a as exporters write them (kept in the text, unread).
constexpr size_t kMaxVertexExtras = 4;

// The tokens after a vertex's x y z: a few finite numbers, or the line is not a vertex skinslide
// understands (a word there may be a mistyped statement joined to the line).
template <typename Fail>
void check_vertex_tail(const std::vector<Token>& tok, Fail&& fail) {
  for (size_t k = 4; k < tok.size(); ++k) {
    const auto x = parse_double(tok[k].text);
    if (!x || !std::isfinite(*x))
      fail("vertex entry " + quoted(tok[k].text) + " after x y z is not " +
           (x ? "finite" : "a number") + " (a vertex is x y z, then w or a colour r g b [a])");
  }
  if (tok.size() - 4 > kMaxVertexExtras)
    fail("vertex has " + std::to_string(tok.size() - 1) + " numbers; at most " +
         std::to_string(3 + kMaxVertexExtras) + " (x y z, then w or a colour r g b [a])");
}

}  // namespace

ObjMesh parse_obj(const std::string& path, std::string bytes) {
  ObjMesh obj;
  std::vector<Token> tok;
  std::vector<Index> face, scratch;
  std::vector<std::pair<long, long long>> forward_refs;  // (line, 1-based index)
  long line = 0;
  const size_t n = bytes.size();
  if (n == 0) throw_input(path, 0, "the file is empty (0 bytes): not an OBJ mesh");
  // A UTF-8 byte-order mark (some Windows tools write one) is not part of the first statement;
  // it stays in the text, so a rewritten frame keeps it.
  size_t pos = bytes.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  size_t eol = 0;
  // One search of the whole text for a NUL byte, instead of one per line; the error still comes
  // when the parse reaches that line, after any error on the lines before it.
  const size_t nul = bytes.find('\0');
  // A bad last line without an end of line is most likely a file cut short (a copy or an export
  // that did not finish): say so.
  auto fail = [&](const std::string& what) {
    const bool cut = eol == n && bytes[n - 1] != '\n';
    throw_input(path, line,
                cut ? what + " (the last line has no end of line: is the file truncated?)" : what);
  };
  while (pos < n) {
    ++line;
    eol = bytes.find('\n', pos);
    if (eol == std::string::npos) eol = n;
    if (nul != std::string::npos && nul >= pos && nul < eol)
      throw_input(path, line, "binary data (NUL byte): not a text OBJ file");
    tokenize(bytes, pos, eol, tok);
    pos = eol + 1;
    if (tok.empty()) continue;
    if (tok.back().text == "\\")
      throw_input(path, line, "line continuation '\\' is not supported; join the lines");
    const std::string_view key = tok[0].text;
    if (misspelt_vertex_or_face(key))
      throw_input(path, line,
                  "unknown statement " + quoted(key) +
                      ": OBJ keywords are lower case and end at a space (`v x y z`, `f a b c`); "
                      "skipped, it would shift every later vertex index");
    if (key == "v") {
      if (tok.size() < 4)
        fail("vertex has " + count_of(tok.size() - 1, "coordinate", "coordinates") + "; 3 needed");
      Vec3 p;
      for (int k = 0; k < 3; ++k) {
        const Token& t = tok[1 + k];
        const auto x = parse_double(t.text);
        if (!x) fail("vertex coordinate " + quoted(t.text) + " is not a number");
        if (!std::isfinite(*x))
          throw_input(path, line,
                      "vertex coordinate " + quoted(t.text) + " is not finite" +
                          (overflows(t.text) ? " (beyond the largest double, 1.8e308)" : ""));
        p[k] = *x;
      }
      check_vertex_tail(tok, fail);
      obj.mesh.positions.push_back(p);
      obj.text.coordinate_spans.push_back({tok[1].begin, tok[3].begin + tok[3].text.size()});
    } else if (key == "f") {
      if (tok.size() < 4)
        fail("face has " + count_of(tok.size() - 1, "vertex", "vertices") + "; at least 3 needed");
      face.clear();
      const long long nv = static_cast<long long>(obj.mesh.positions.size());
      for (size_t k = 1; k < tok.size(); ++k) {
        const std::string_view entry = tok[k].text;
        if (std::count(entry.begin(), entry.end(), '/') > kMaxCornerSlashes)
          fail("face corner " + quoted(entry) +
               " has more than 3 parts; a corner is v, v/vt, v//vn or v/vt/vn");
        const std::string_view first = entry.substr(0, entry.find('/'));
        const auto idx = parse_integer(first);
        // An index out of range as written, or beyond a long long (quoted then).
        const auto before_first = [&](const std::string& index) {
          throw_input(path, line,
                      "relative face index " + index + " reaches before vertex 1 (" +
                          std::to_string(nv) + " vertices defined so far)");
        };
        const auto too_large = [&](const std::string& index) {
          throw_input(path, line, "face index " + index + " is too large");
        };
        if (!idx && whole_number_text(first))
          first[0] == '-' ? before_first(quoted(first)) : too_large(quoted(first));
        if (!idx) fail("face entry " + quoted(entry) + " is not a vertex index");
        check_corner_parts(entry, fail);
        long long v = *idx;
        if (v == 0) throw_input(path, line, "face index 0 (OBJ indices start at 1)");
        if (v < 0) {
          v = nv + v;
          if (v < 0) before_first(std::to_string(*idx));
        } else {
          if (v > nv) forward_refs.emplace_back(line, v);
          v -= 1;
        }
        if (v > 0x7fffffffLL) too_large(std::to_string(*idx));
        face.push_back(static_cast<Index>(v));
      }
      Index dup = 0;
      if (repeated_vertex(face, scratch, dup))
        fail("face uses vertex " + std::to_string(dup + 1) + " twice (degenerate face)");
      obj.mesh.add_face(face);
      obj.face_lines.push_back(line);
    }
    // Every other statement (vt, vn, g, o, s, usemtl, mtllib, l, p, ...) is kept as text only.
  }
  const long long nv = static_cast<long long>(obj.mesh.positions.size());
  if (nv == 0) throw_input(path, 0, "no vertices (`v` lines): not an OBJ mesh");
  const bool cut = bytes.back() != '\n';
  for (const auto& [ln, v] : forward_refs)
    if (v > nv)
      throw_input(path, ln,
                  "face index " + std::to_string(v) + " is out of range (the file has " +
                      std::to_string(nv) + " vertices" +
                      (cut ? "; its last line has no end of line: is the file truncated?)" : ")"));
  obj.text.bytes = std::move(bytes);
  return obj;
}

ObjMesh read_obj(const std::string& path) { return parse_obj(path, read_file(path)); }

std::array<std::uint64_t, 6> coordinate_tokens(const ObjText& text, size_t v) {
  const auto [begin, end] = text.coordinate_spans[v];
  const char* bytes = text.bytes.data();
  std::array<std::uint64_t, 6> out{};
  std::uint64_t i = begin;
  for (int k = 0; k < 3; ++k) {
    while (i < end && is_space(bytes[i])) ++i;
    out[2 * k] = i;
    while (i < end && !is_space(bytes[i])) ++i;
    out[2 * k + 1] = i;
  }
  return out;
}

}  // namespace skinslide
