// libFuzzer target: the patch-file parser and the face selection.
// Any input either parses or throws skinslide::Error(Input); a selection is ascending, unique and
// inside the face count.

#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/error.h"
#include "io/patch_file.h"

using namespace skinslide;

namespace {

constexpr Index kFaces = 1000;

void require(bool cond) {
  if (!cond) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const PatchSelection sel = parse_patch("fuzz.txt", text);
    for (const FaceRange& r : sel.ranges) require(0 <= r.first && r.first <= r.last && r.line >= 1);
    const std::vector<Index> faces = selected_faces(sel, kFaces);
    require(!faces.empty());
    for (size_t i = 0; i < faces.size(); ++i) {
      require(faces[i] >= 0 && faces[i] < kFaces);
      if (i > 0) require(faces[i - 1] < faces[i]);
    }
  } catch (const Error& e) {
    require(e.kind() == ErrorKind::Input);
  }
  return 0;
}
