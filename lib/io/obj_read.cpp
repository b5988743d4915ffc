#include "io/obj_read.h"

#include <cmath>
#include <string_view>

#include "core/error.h"
#include "io/atomic_write.h"
#include "io/number_format.h"

namespace skinslide {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

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
    while (i < end && !is_space(bytes[i]) && bytes[i] != '#') ++i;
    out.push_back({std::string_view(bytes.data() + s, i - s), s});
  }
}

std::string quoted(std::string_view t) {
  constexpr size_t kMax = 40;
  std::string s(t.substr(0, kMax));
  if (t.size() > kMax) s += "...";
  return "'" + s + "'";
}

}  // namespace

ObjMesh parse_obj(const std::string& path, std::string bytes) {
  ObjMesh obj;
  std::vector<Token> tok;
  std::vector<Index> face;
  std::vector<std::pair<long, long long>> forward_refs;  // (line, 1-based index)
  long line = 0;
  size_t pos = 0;
  const size_t n = bytes.size();
  while (pos < n) {
    ++line;
    size_t eol = bytes.find('\n', pos);
    if (eol == std::string::npos) eol = n;
    const std::string_view raw(bytes.data() + pos, eol - pos);
    if (raw.find('\0') != std::string_view::npos)
      throw_input(path, line, "binary data (NUL byte): not a text OBJ file");
    tokenize(bytes, pos, eol, tok);
    pos = eol + 1;
    if (tok.empty()) continue;
    if (tok.back().text == "\\")
      throw_input(path, line, "line continuation '\\' is not supported; join the lines");
    const std::string_view key = tok[0].text;
    if (key == "v") {
      if (tok.size() < 4)
        throw_input(path, line,
                    "vertex has " + std::to_string(tok.size() - 1) + " coordinates; 3 needed");
      Vec3 p;
      std::array<std::uint64_t, 6> span{};
      for (int k = 0; k < 3; ++k) {
        const Token& t = tok[1 + k];
        const auto x = parse_double(t.text);
        if (!x) throw_input(path, line, "vertex coordinate " + quoted(t.text) + " is not a number");
        if (!std::isfinite(*x))
          throw_input(path, line, "vertex coordinate " + quoted(t.text) + " is not finite");
        p[k] = *x;
        span[2 * k] = t.begin;
        span[2 * k + 1] = t.begin + t.text.size();
      }
      obj.mesh.positions.push_back(p);
      obj.text.coordinate_spans.push_back(span);
      obj.vertex_lines.push_back(line);
    } else if (key == "f") {
      if (tok.size() < 4)
        throw_input(path, line,
                    "face has " + std::to_string(tok.size() - 1) + " vertices; at least 3 needed");
      face.clear();
      const long long nv = static_cast<long long>(obj.mesh.positions.size());
      for (size_t k = 1; k < tok.size(); ++k) {
        const std::string_view entry = tok[k].text;
        const std::string_view first = entry.substr(0, entry.find('/'));
        const auto idx = parse_integer(first);
        if (!idx) throw_input(path, line, "face entry " + quoted(entry) + " is not a vertex index");
        long long v = *idx;
        if (v == 0) throw_input(path, line, "face index 0 (OBJ indices start at 1)");
        if (v < 0) {
          v = nv + v;
          if (v < 0)
            throw_input(path, line,
                        "relative face index " + std::to_string(*idx) + " reaches before vertex 1 (" +
                            std::to_string(nv) + " vertices defined so far)");
        } else {
          if (v > nv) forward_refs.emplace_back(line, v);
          v -= 1;
        }
        if (v > 0x7fffffffLL) throw_input(path, line, "face index " + std::to_string(*idx) + " is too large");
        face.push_back(static_cast<Index>(v));
      }
      for (size_t a = 0; a < face.size(); ++a)
        for (size_t b = a + 1; b < face.size(); ++b)
          if (face[a] == face[b])
            throw_input(path, line,
                        "face uses vertex " + std::to_string(face[a] + 1) +
                            " twice (degenerate face)");
      obj.mesh.add_face(face);
      obj.face_lines.push_back(line);
    }
    // Every other statement (vt, vn, g, o, s, usemtl, mtllib, l, p, ...) is kept as text only.
  }
  const long long nv = static_cast<long long>(obj.mesh.positions.size());
  for (const auto& [ln, v] : forward_refs)
    if (v > nv)
      throw_input(path, ln,
                  "face index " + std::to_string(v) + " is out of range (the file has " +
                      std::to_string(nv) + " vertices)");
  if (nv == 0) throw_input(path, 0, "no vertices (`v` lines): empty or not an OBJ file");
  obj.text.bytes = std::move(bytes);
  return obj;
}

ObjMesh read_obj(const std::string& path) { return parse_obj(path, read_file(path)); }

}  // namespace skinslide
