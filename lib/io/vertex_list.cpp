#include "io/vertex_list.h"

#include <cmath>
#include <string_view>

#include "core/error.h"
#include "io/atomic_write.h"
#include "core/number_format.h"
#include "io/obj_read.h"
#include "io/token_lines.h"

namespace skinslide {
namespace {

double weight_value(const std::string& path, long line, std::string_view t) {
  const auto w = parse_double(t);
  if (!w) throw_input(path, line, quoted_token(t) + " is not a number");
  if (!(*w >= 0 && *w <= 1))
    throw_input(path, line, "weight " + std::string(t) + " is outside [0, 1]");
  return *w;
}

std::optional<long long> vertex_id(std::string_view t) {
  if (t.empty() || t.front() == '+' || t.front() == '-') return std::nullopt;
  return parse_integer(t);
}

}  // namespace

std::vector<double> parse_weights(const std::string& path, const std::string& text,
                                  Index vertex_count) {
  enum class Layout { Unknown, Dense, Pairs } layout = Layout::Unknown;
  std::vector<double> w;
  std::vector<long> listed_at;  // pairs: line that set each vertex, 0 = not listed
  long first_line = 0;
  for_each_token_line(
      path, text, "a text file", [&](long line, const std::vector<std::string_view>& tok) {
        if (tok.empty()) return;
        if (layout == Layout::Unknown) {
          first_line = line;
          if (tok.size() == 1) {
            layout = Layout::Dense;
          } else if (tok.size() == 2) {
            layout = Layout::Pairs;
            w.assign(vertex_count, 0.0);
            listed_at.assign(vertex_count, 0);
          }
        }
        if (layout == Layout::Dense) {
          if (tok.size() != 1)
            throw_input(path, line,
                        "has " + std::to_string(tok.size()) + " numbers; line " +
                            std::to_string(first_line) +
                            " starts a one-weight-a-line file (vertex order)");
          if (static_cast<Index>(w.size()) == vertex_count)
            throw_input(
                path, line,
                "more weights than the bind's " + std::to_string(vertex_count) + " vertices");
          w.push_back(weight_value(path, line, tok[0]));
        } else if (layout == Layout::Pairs) {
          if (tok.size() != 2)
            throw_input(path, line,
                        "has " + std::to_string(tok.size()) + " numbers; line " +
                            std::to_string(first_line) + " starts an 'index weight' file");
          const auto id = vertex_id(tok[0]);
          if (!id) throw_input(path, line, quoted_token(tok[0]) + " is not a vertex id");
          if (*id >= vertex_count)
            throw_input(path, line,
                        "vertex " + std::string(tok[0]) + " is out of range (the bind has " +
                            std::to_string(vertex_count) + " vertices, numbered 0 to " +
                            std::to_string(vertex_count - 1) + ")");
          if (listed_at[*id])
            throw_input(path, line,
                        "vertex " + std::string(tok[0]) + " is already given a weight on line " +
                            std::to_string(listed_at[*id]));
          w[*id] = weight_value(path, line, tok[1]);
          listed_at[*id] = line;
        } else {
          throw_input(path, line,
                      "expected one weight a line or 'index weight' pairs; found " +
                          std::to_string(tok.size()) + " numbers");
        }
      });
  if (layout == Layout::Unknown) throw_input(path, 0, "holds no weights");
  if (layout == Layout::Dense && static_cast<Index>(w.size()) != vertex_count)
    throw_input(path, 0,
                "has " + std::to_string(w.size()) + " weights; the bind has " +
                    std::to_string(vertex_count) +
                    " vertices (one weight a line in vertex order, or 'index weight' pairs)");
  return w;
}

std::vector<double> read_weights(const std::string& path, Index vertex_count) {
  return parse_weights(path, read_file(path), vertex_count);
}

std::vector<Index> parse_vertex_list(const std::string& path, const std::string& text,
                                     Index vertex_count) {
  std::vector<char> in(vertex_count, 0);
  for_each_token_line(
      path, text, "a text file", [&](long line, const std::vector<std::string_view>& tokens) {
        for (std::string_view tok : tokens) {
          std::string_view body = tok;
          char sep = '-';
          const size_t bracket = tok.find("vtx[");
          if (bracket != std::string_view::npos && tok.back() == ']' &&
              (bracket == 0 || tok[bracket - 1] == '.')) {
            body = tok.substr(bracket + 4, tok.size() - bracket - 5);
            sep = ':';
          }
          const size_t s = body.find(sep, 1);
          const auto a = vertex_id(body.substr(0, s));
          const auto b = s == std::string_view::npos ? a : vertex_id(body.substr(s + 1));
          if (!a || !b)
            throw_input(path, line,
                        "unknown token " + quoted_token(tok) +
                            ": expected a vertex id (12), a range (12-40) or a Maya "
                            "component (pBody.vtx[12:40])");
          if (*a > *b) throw_input(path, line, "range " + quoted_token(tok) + " runs backwards");
          if (*b >= vertex_count)
            throw_input(path, line,
                        "vertex " + std::to_string(*b) + " is out of range (the bind has " +
                            std::to_string(vertex_count) + " vertices, numbered 0 to " +
                            std::to_string(vertex_count - 1) + ")");
          for (long long v = *a; v <= *b; ++v) in[v] = 1;
        }
      });
  std::vector<Index> ids;
  for (Index v = 0; v < vertex_count; ++v)
    if (in[v]) ids.push_back(v);
  return ids;
}

std::vector<Index> read_vertex_list(const std::string& path, Index vertex_count) {
  return parse_vertex_list(path, read_file(path), vertex_count);
}

std::vector<double> obj_color_weights(const std::string& path, const ObjText& obj, int channel) {
  std::vector<double> w(obj.coordinate_spans.size());
  const std::string& text = obj.bytes;
  long line = 1;
  size_t counted = 0;  // newlines before this offset are in `line`
  for (size_t v = 0; v < w.size(); ++v) {
    const size_t z_end = obj.coordinate_spans[v][1];
    for (; counted < z_end; ++counted)
      if (text[counted] == '\n') ++line;
    size_t eol = text.find('\n', z_end);
    if (eol == std::string::npos) eol = text.size();
    std::string_view rest(text.data() + z_end, eol - z_end);
    rest = rest.substr(0, rest.find('#'));
    std::vector<std::string_view> tok;
    size_t i = 0;
    while (i < rest.size()) {
      while (i < rest.size() && (rest[i] == ' ' || rest[i] == '\t' || rest[i] == '\r')) ++i;
      if (i >= rest.size()) break;
      const size_t s = i;
      while (i < rest.size() && !(rest[i] == ' ' || rest[i] == '\t' || rest[i] == '\r')) ++i;
      tok.push_back(rest.substr(s, i - s));
    }
    // r g b, or r g b a as some exporters write it: the alpha is not a channel a weight may come
    // from, and is ignored (the OBJ reader has checked it is a number).
    if (tok.size() != 3 && tok.size() != 4)
      throw_input(path, line,
                  "vertex " + std::to_string(v) +
                      " has no colour: expected 'v x y z r g b' or 'v x y z r g b a' for slide "
                      "weights from vertex colours");
    const auto c = parse_double(tok[channel]);
    if (!c) throw_input(path, line, "colour " + quoted_token(tok[channel]) + " is not a number");
    if (!(*c >= 0 && *c <= 1))
      throw_input(path, line,
                  "colour " + std::string(tok[channel]) +
                      " is outside [0, 1] (slide weights are colours in 0..1)");
    w[v] = *c;
  }
  return w;
}

}  // namespace skinslide
