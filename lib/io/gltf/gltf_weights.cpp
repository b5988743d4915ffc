#include "io/gltf/gltf_weights.h"

#include <cmath>

#include "core/error.h"
#include "io/gltf/gltf_accessor.h"
#include "io/gltf/gltf_document.h"
#include "core/number_format.h"

namespace skinslide {
namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw Error(ErrorKind::Input, where + ": " + what);
}

std::string component_name(int component_type, bool normalized) {
  std::string s;
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      s = "byte";
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      s = "unsigned byte";
      break;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      s = "short";
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      s = "unsigned short";
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      s = "unsigned int";
      break;
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      s = "float";
      break;
    default:
      s = "component type " + std::to_string(component_type);
  }
  return normalized ? "normalized " + s : s;
}

bool is_weight_component(const tinygltf::Accessor& acc) {
  if (acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return !acc.normalized;
  return acc.normalized && (acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                            acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
}

}  // namespace

std::vector<double> gltf_attribute_weights(const MeshFile& file, const std::string& name) {
  if (!file.gltf)
    throw Error(ErrorKind::Usage, file.path +
                                      ": slide weights from a vertex attribute need a glTF "
                                      "or GLB mesh file");
  const GltfDocument& doc = *file.gltf;
  const tinygltf::Model& model = doc.model;
  const tinygltf::Mesh& mesh = model.meshes[doc.mesh];
  std::vector<double> weights(file.mesh.vertex_count());
  std::vector<char> set(weights.size(), 0);
  for (const GltfPrimitive& gp : doc.primitives) {
    const tinygltf::Primitive& prim = mesh.primitives[gp.primitive];
    const std::string where = file.path + ": mesh " + std::to_string(doc.mesh) + " primitive " +
                              std::to_string(gp.primitive);
    const auto it = prim.attributes.find(name);
    if (it == prim.attributes.end())
      fail(where,
           "has no " + name + " attribute (slide weights are read from every triangle primitive)");
    const int index = it->second;
    const std::string aw = where + ": " + name + " accessor " + std::to_string(index);
    if (index < 0 || index >= static_cast<int>(model.accessors.size())) fail(aw, "does not exist");
    const tinygltf::Accessor& acc = model.accessors[index];
    if (acc.type != TINYGLTF_TYPE_SCALAR || !is_weight_component(acc))
      fail(aw, "is " + gltf_type_name(acc.type) + " " +
                   component_name(acc.componentType, acc.normalized) +
                   "; slide weights need SCALAR float, normalized unsigned byte or normalized "
                   "unsigned short");
    if (static_cast<Index>(acc.count) != gp.raw_count)
      fail(aw, "has " + std::to_string(acc.count) + " elements, POSITION has " +
                   std::to_string(gp.raw_count));
    const std::vector<double> values = gltf_accessor_values(model, index, aw);
    for (Index i = 0; i < gp.raw_count; ++i) {
      const double w = values[i];
      if (!std::isfinite(w)) fail(aw, "element " + std::to_string(i) + " is not finite");
      if (!(w >= 0 && w <= 1))
        fail(aw, "element " + std::to_string(i) + " is " + format_double(w) +
                     ", outside [0, 1] (slide weights are 0..1)");
      // Raw ids ascend, so the first raw copy of each welded vertex sets its weight, as it set
      // its position.
      const Index v = doc.welded[gp.raw_offset + i];
      if (!set[v]) {
        weights[v] = w;
        set[v] = 1;
      }
    }
  }
  return weights;
}

}  // namespace skinslide
