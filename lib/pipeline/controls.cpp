#include "pipeline/controls.h"

#include <array>
#include <string_view>

#include "core/error.h"
#include "core/number_format.h"
#include "io/gltf/gltf_weights.h"
#include "io/vertex_list.h"

namespace skinslide {
namespace {

// "a,b,c,d" -> four vertex ids.
std::array<Index, 4> parse_corners(const std::string& text) {
  std::array<Index, 4> c{};
  size_t pos = 0;
  for (int j = 0; j < 4; ++j) {
    const size_t comma = j < 3 ? text.find(',', pos) : text.size();
    const auto id = comma == std::string::npos
                        ? std::nullopt
                        : parse_integer(std::string_view(text).substr(pos, comma - pos));
    if (!id || *id < 0 || *id > 2147483647LL || (j < 3 && comma == text.size()))
      throw Error(ErrorKind::Usage, "--corners " + text +
                                        ": expected four vertex ids a,b,c,d (the outer loop's "
                                        "corners in walking order)");
    c[j] = static_cast<Index>(*id);
    pos = comma + 1;
  }
  return c;
}

}  // namespace

SlideControls slide_controls(const RunOptions& o, const MeshFile& bind, RunReport& report) {
  SlideControls c;
  const Index nv = bind.mesh.vertex_count();
  if (!o.weights.empty()) {
    c.weight = read_weights(o.weights, nv);
    report.weights = o.weights;
  } else if (!o.weights_from_obj_color.empty()) {
    if (!bind.obj)
      throw Error(ErrorKind::Usage,
                  "--weights-from-obj-color needs an OBJ bind; " + o.bind + " is not one");
    const std::string& color = o.weights_from_obj_color;
    const int channel = color == "r" ? 0 : color == "g" ? 1 : 2;
    c.weight = obj_color_weights(o.bind, *bind.obj, channel);
    report.weights = o.bind + " (vertex colour " + color + ")";
  } else if (!o.weights_from_gltf_attribute.empty()) {
    c.weight = gltf_attribute_weights(bind, o.weights_from_gltf_attribute);
    report.weights = o.bind + " (glTF attribute " + o.weights_from_gltf_attribute + ")";
  }
  c.strength = o.strength;
  report.strength = o.strength;
  if (!o.pin.empty()) {
    c.pins = read_vertex_list(o.pin, nv);
    report.pins = o.pin;
    report.pins_requested = static_cast<Index>(c.pins.size());
  }
  for (const std::string& t : o.corners) c.corners.push_back(parse_corners(t));
  for (Index v : o.outer_loop_vertices) c.outer_loop_vertices.push_back(v);
  return c;
}

}  // namespace skinslide
