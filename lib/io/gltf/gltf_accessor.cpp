#include "io/gltf/gltf_accessor.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "core/error.h"

namespace skinslide {
namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw Error(ErrorKind::Input, where + ": " + what);
}

int component_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

// glTF data is little-endian; so is every platform skinslide builds on, so memcpy suffices.
double component(const unsigned char* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      std::int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      std::uint8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return normalized ? v / 4294967295.0 : v;
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

bool is_matrix(int type) {
  return type == TINYGLTF_TYPE_MAT2 || type == TINYGLTF_TYPE_MAT3 || type == TINYGLTF_TYPE_MAT4;
}

// Layout of one element: matrices with 1- or 2-byte components pad each column to 4 bytes
// (glTF 2.0, section 3.6.2.4 "Data alignment").
struct ElementLayout {
  int components = 0;
  int rows = 0;           // components per column (= components for vectors)
  int column_stride = 0;  // bytes
  int size = 0;           // bytes of one element
};

ElementLayout element_layout(int type, int component_type) {
  ElementLayout l;
  l.components = gltf_component_count(type);
  const int cs = component_size(component_type);
  if (is_matrix(type)) {
    l.rows = type == TINYGLTF_TYPE_MAT2 ? 2 : type == TINYGLTF_TYPE_MAT3 ? 3 : 4;
    l.column_stride = (l.rows * cs + 3) / 4 * 4;
    l.size = l.column_stride * (l.components / l.rows);
  } else {
    l.rows = l.components;
    l.column_stride = l.components * cs;
    l.size = l.column_stride;
  }
  return l;
}

// The bytes [begin, begin+length) of buffer view `view`, checked against the buffer.
const unsigned char* view_data(const tinygltf::Model& model, int view, const std::string& where,
                               const char* role, std::size_t* length) {
  if (view < 0 || view >= static_cast<int>(model.bufferViews.size()))
    fail(where, std::string(role) + " buffer view " + std::to_string(view) + " does not exist");
  const tinygltf::BufferView& bv = model.bufferViews[view];
  const std::string name = std::string(role) + " buffer view " + std::to_string(view);
  for (const char* ext : {"EXT_meshopt_compression", "KHR_meshopt_compression"})
    if (bv.extensions.count(ext))
      fail(where, name + " is compressed with " + ext + ", which skinslide cannot decode");
  if (bv.buffer < 0 || bv.buffer >= static_cast<int>(model.buffers.size()))
    fail(where, name + ": buffer " + std::to_string(bv.buffer) + " does not exist");
  const std::vector<unsigned char>& data = model.buffers[bv.buffer].data;
  if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
    fail(where, name + ": bytes " + std::to_string(bv.byteOffset) + "+" +
                    std::to_string(bv.byteLength) + " run past buffer " +
                    std::to_string(bv.buffer) + " (" + std::to_string(data.size()) + " bytes)");
  *length = bv.byteLength;
  return data.data() + bv.byteOffset;
}

// 2^26 elements: 1.5 GB of decoded VEC3 doubles.
constexpr std::size_t kMaxElementsWithoutView = std::size_t{1} << 26;

}  // namespace

std::string gltf_type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return "type " + std::to_string(type);
  }
}

int gltf_component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

std::vector<double> gltf_accessor_values(const tinygltf::Model& model, int index,
                                         const std::string& where) {
  if (index < 0 || index >= static_cast<int>(model.accessors.size()))
    fail(where, "accessor " + std::to_string(index) + " does not exist");
  const tinygltf::Accessor& acc = model.accessors[index];
  const ElementLayout layout = element_layout(acc.type, acc.componentType);
  const int cs = component_size(acc.componentType);
  if (layout.components == 0 || cs == 0)
    fail(where, "unsupported type " + std::to_string(acc.type) + " / component type " +
                    std::to_string(acc.componentType));
  const std::size_t n = acc.count;
  const int nc = layout.components;
  // Every bound is checked before anything is allocated: a count read from the file must not
  // decide how much memory is taken (a few bytes of JSON could ask for 100 GB).
  const unsigned char* base = nullptr;
  std::size_t stride = 0;
  if (acc.bufferView >= 0) {
    std::size_t length = 0;
    base = view_data(model, acc.bufferView, where, "its", &length);
    const std::size_t view_stride = model.bufferViews[acc.bufferView].byteStride;
    stride = view_stride ? view_stride : static_cast<std::size_t>(layout.size);
    if (view_stride && view_stride < static_cast<std::size_t>(layout.size))
      fail(where, "byteStride " + std::to_string(view_stride) + " is smaller than an element (" +
                      std::to_string(layout.size) + " bytes)");
    if (n > 0 && (acc.byteOffset > length || (n - 1) > (length - acc.byteOffset) / stride ||
                  (n - 1) * stride + layout.size > length - acc.byteOffset))
      fail(where, std::to_string(n) + " elements from byte " + std::to_string(acc.byteOffset) +
                      " run past the end of buffer view " + std::to_string(acc.bufferView) + " (" +
                      std::to_string(length) + " bytes)");
  } else if (n > kMaxElementsWithoutView) {
    // Without a buffer view the elements are zeros (then sparse values): nothing in the file
    // bounds the count, so skinslide does.
    fail(where, "has " + std::to_string(n) +
                    " elements and no buffer view; skinslide reads at most " +
                    std::to_string(kMaxElementsWithoutView) + " elements without one");
  }
  std::vector<double> out(n * nc, 0.0);

  auto read_element = [&](const unsigned char* p, double* dst) {
    for (int c = 0; c < nc; ++c) {
      const int col = c / layout.rows, row = c % layout.rows;
      dst[c] =
          component(p + col * layout.column_stride + row * cs, acc.componentType, acc.normalized);
    }
  };

  if (base) {
    for (std::size_t i = 0; i < n; ++i)
      read_element(base + acc.byteOffset + i * stride, out.data() + i * nc);
  }

  if (acc.sparse.isSparse) {
    const std::size_t k = static_cast<std::size_t>(std::max(acc.sparse.count, 0));
    const int ics = component_size(acc.sparse.indices.componentType);
    if (ics == 0 || acc.sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
        acc.sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
        acc.sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
      fail(where, "sparse indices have component type " +
                      std::to_string(acc.sparse.indices.componentType));
    std::size_t ilen = 0, vlen = 0;
    const unsigned char* ip =
        view_data(model, acc.sparse.indices.bufferView, where, "sparse indices", &ilen);
    const unsigned char* vp =
        view_data(model, acc.sparse.values.bufferView, where, "sparse values", &vlen);
    const std::size_t ioff = static_cast<std::size_t>(std::max(acc.sparse.indices.byteOffset, 0));
    const std::size_t voff = static_cast<std::size_t>(std::max(acc.sparse.values.byteOffset, 0));
    if (ioff > ilen || k * ics > ilen - ioff || voff > vlen || k * layout.size > vlen - voff)
      fail(where, "sparse " + std::to_string(k) + " entries run past their buffer views");
    for (std::size_t s = 0; s < k; ++s) {
      const double target = component(ip + ioff + s * ics, acc.sparse.indices.componentType, false);
      if (target >= static_cast<double>(n))
        fail(where, "sparse index " + std::to_string(static_cast<long long>(target)) +
                        " is out of range (count " + std::to_string(n) + ")");
      read_element(vp + voff + s * layout.size, out.data() + static_cast<std::size_t>(target) * nc);
    }
  }
  return out;
}

std::size_t gltf_element_offset(const tinygltf::Model& model, int index, std::size_t element) {
  const tinygltf::Accessor& acc = model.accessors[index];
  const tinygltf::BufferView& bv = model.bufferViews[acc.bufferView];
  const ElementLayout layout = element_layout(acc.type, acc.componentType);
  const std::size_t stride = bv.byteStride ? bv.byteStride : static_cast<std::size_t>(layout.size);
  return bv.byteOffset + acc.byteOffset + element * stride;
}

}  // namespace skinslide
