#include "io/obj_rewrite.h"

#include "core/check.h"
#include "io/number_format.h"

namespace skinslide {

std::string rewrite_obj(const ObjText& obj, const Positions3& original,
                        const Positions3& positions) {
  SKINSLIDE_CHECK(original.size() == obj.coordinate_spans.size(), "vertex count of OBJ text");
  SKINSLIDE_CHECK(positions.size() == original.size(), "vertex count of new positions");
  // Reserved for the longest numbers the changed coordinates can take (shortest round-trip
  // text of a double: at most 24 characters): growing by doubling would hold the old buffer and
  // one of twice its size at once, about 190 MB for a 1M-vertex frame.
  constexpr std::uint64_t kLongestDouble = 24;
  std::uint64_t bound = obj.bytes.size();
  for (size_t v = 0; v < positions.size(); ++v) {
    if (positions[v] == original[v]) continue;
    const auto& span = obj.coordinate_spans[v];
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t length = span[2 * k + 1] - span[2 * k];
      if (length < kLongestDouble) bound += kLongestDouble - length;
    }
  }
  std::string out;
  out.reserve(bound);
  std::uint64_t copied = 0;  // bytes of obj.bytes already copied
  for (size_t v = 0; v < positions.size(); ++v) {
    if (positions[v] == original[v]) continue;
    const auto& span = obj.coordinate_spans[v];
    for (int k = 0; k < 3; ++k) {
      out.append(obj.bytes, copied, span[2 * k] - copied);
      out += format_double(positions[v][k]);
      copied = span[2 * k + 1];
    }
  }
  out.append(obj.bytes, copied, std::string::npos);
  return out;
}

}  // namespace skinslide
