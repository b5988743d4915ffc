#include "io/obj_rewrite.h"

#include "core/check.h"
#include "io/atomic_write.h"
#include "core/number_format.h"

namespace skinslide {
namespace {

// The rewritten text, piece by piece: the kept bytes between changed coordinates, and each
// changed coordinate's new text.
template <typename Emit>
void rewrite(const ObjText& obj, const Positions3& original, const Positions3& positions,
             Emit&& emit) {
  SKINSLIDE_CHECK(original.size() == obj.coordinate_spans.size(), "vertex count of OBJ text");
  SKINSLIDE_CHECK(positions.size() == original.size(), "vertex count of new positions");
  const std::string_view bytes = obj.bytes;
  std::uint64_t copied = 0;  // bytes of obj.bytes already emitted
  for (size_t v = 0; v < positions.size(); ++v) {
    if (positions[v] == original[v]) continue;
    const std::array<std::uint64_t, 6> span = coordinate_tokens(obj, v);
    for (int k = 0; k < 3; ++k) {
      emit(bytes.substr(copied, span[2 * k] - copied));
      emit(double_text(positions[v][k]).view());
      copied = span[2 * k + 1];
    }
  }
  emit(bytes.substr(copied));
}

}  // namespace

std::string rewrite_obj(const ObjText& obj, const Positions3& original,
                        const Positions3& positions) {
  std::string out;
  out.reserve(obj.bytes.size());
  rewrite(obj, original, positions, [&](std::string_view piece) { out.append(piece); });
  return out;
}

void write_rewritten_obj(const std::string& path, const ObjText& obj, const Positions3& original,
                         const Positions3& positions) {
  AtomicFile file(path);
  rewrite(obj, original, positions, [&](std::string_view piece) { file.write(piece); });
  file.commit();
}

}  // namespace skinslide
