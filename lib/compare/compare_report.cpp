#include "compare/compare_report.h"

#include "core/version.h"
#include "core/json_text.h"
#include "core/number_format.h"

namespace skinslide {
namespace {

std::string boolean(bool b) { return b ? "true" : "false"; }

std::string frame_json(const ComparedFrame& f) {
  const FrameDifference& d = f.difference;
  return "{\"a\": " + json_string(f.a) + ", \"b\": " + json_string(f.b) +
         ", \"diagonal\": " + format_double(f.diagonal) +
         ", \"max_distance\": " + format_double(d.max_distance) +
         ", \"vertex\": " + std::to_string(d.vertex) +
         ", \"turned_faces\": " + std::to_string(d.turned_faces) +
         ", \"first_turned_face\": " + std::to_string(d.first_turned_face) +
         ", \"differs\": " + boolean(f.differs) + "}";
}

std::string names_json(const std::vector<std::string>& names) {
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i) text += (i ? ", " : "") + json_string(names[i]);
  return "[" + text + "]";
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
  return "{\n  \"skinslide\": " + json_string(version()) + ",\n  \"a\": " + json_string(r.a) +
         ",\n  \"b\": " + json_string(r.b) + ",\n  \"tolerance\": " + format_double(r.tolerance) +
         ",\n  \"diagonal\": " + (r.diagonal_from.empty() ? "null" : format_double(r.diagonal)) +
         ",\n  \"diagonal_from\": " +
         (r.diagonal_from.empty() ? "null" : json_string(r.diagonal_from)) +
         ",\n  \"faces_checked\": " + boolean(r.faces_checked) + ",\n  \"frames\": " + frames +
         ",\n  \"only_in_a\": " + names_json(r.only_in_a) +
         ",\n  \"only_in_b\": " + names_json(r.only_in_b) +
         ",\n  \"differing_frames\": " + std::to_string(r.differing()) +
         ",\n  \"largest\": " + largest + ",\n  \"same\": " + boolean(r.differing() == 0) + "\n}\n";
}

}  // namespace skinslide
