// Reading and editing glTF accessor data: strides, normalized and quantized integers, sparse
// substitution, bounds checks. Internal to io/ (it takes tinygltf types).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace skinslide {

/// Components of one element of a TINYGLTF_TYPE_* (SCALAR 1 ... MAT4 16); 0 when unknown.
int gltf_component_count(int type);

/// "SCALAR", "VEC2", ... "MAT4" for a TINYGLTF_TYPE_*; "type N" when unknown.
std::string gltf_type_name(int type);

/// Every element of accessor `index` as doubles, row-major #count x components (matrices in
/// glTF's column-major order). Integer components are converted as glTF says: `normalized`
/// ones to [-1, 1] or [0, 1] (signed: max(c / (2^(n-1) - 1), -1)), others to their value.
/// A sparse accessor gets its substitutions; one without bufferView starts from zeros.
/// \param where prefix of error messages, e.g. "f.glb: mesh 0 primitive 1: POSITION accessor 3"
/// \throw Error(Input) on a bad index, component type, an element or sparse index out of its
///        buffer view or buffer, or a compressed (EXT_meshopt_compression) buffer view.
std::vector<double> gltf_accessor_values(const tinygltf::Model& model, int index,
                                         const std::string& where);

/// Byte address of element `element` of a plain (non-sparse, with bufferView) accessor in its
/// buffer's data. \pre the accessor was read by gltf_accessor_values (so it is in bounds).
std::size_t gltf_element_offset(const tinygltf::Model& model, int index, std::size_t element);

}  // namespace skinslide
