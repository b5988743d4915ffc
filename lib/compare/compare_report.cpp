#include "compare/compare_report.h"

#include <cstdio>

#include "core/version.h"
#include "io/number_format.h"

namespace skinslide {
namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(c));
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string boolean(bool b) { return b ? "true" : "false"; }

std::string frame_json(const ComparedFrame& f) {
  const FrameDifference& d = f.difference;
  return "{\"a\": " + quoted(f.a) + ", \"b\": " + quoted(f.b) +
         ", \"max_distance\": " + format_double(d.max_distance) +
         ", \"vertex\": " + std::to_string(d.vertex) +
         ", \"turned_faces\": " + std::to_string(d.turned_faces) +
         ", \"first_turned_face\": " + std::to_string(d.first_turned_face) +
         ", \"differs\": " + boolean(f.differs) + "}";
}

}  // namespace

std::string compare_report_json(const CompareResult& r) {
  std::string frames;
  for (std::size_t i = 0; i < r.frames.size(); ++i)
    frames += (i ? ",\n    " : "\n    ") + frame_json(r.frames[i]);
  frames = r.frames.empty() ? "[]" : "[" + frames + "\n  ]";
  const long long k = r.largest();
  const std::string largest =
      k < 0
          ? "null"
          : "{\"frame\": " + std::to_string(k) + ", \"max_distance\": " +
                format_double(r.frames[static_cast<std::size_t>(k)].difference.max_distance) + "}";
  return "{\n  \"skinslide\": " + quoted(version()) + ",\n  \"a\": " + quoted(r.a) +
         ",\n  \"b\": " + quoted(r.b) + ",\n  \"tolerance\": " + format_double(r.tolerance) +
         ",\n  \"diagonal\": " + format_double(r.diagonal) +
         ",\n  \"diagonal_from\": " + quoted(r.diagonal_from) +
         ",\n  \"faces_checked\": " + boolean(r.faces_checked) + ",\n  \"frames\": " + frames +
         ",\n  \"differing_frames\": " + std::to_string(r.differing()) +
         ",\n  \"largest\": " + largest + ",\n  \"same\": " + boolean(r.differing() == 0) + "\n}\n";
}

}  // namespace skinslide
