#include "io/patch_file.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace skinslide {
namespace {

std::string error_of(const std::string& text, Index faces = 100) {
  try {
    selected_faces(parse_patch("p.txt", text), faces);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    return e.what();
  }
  return "";
}

TEST(PatchFile, ReadsIdsRangesAndMayaComponents) {
  const PatchSelection s =
      parse_patch("p.txt", "# faces\n3 1, 2\n10-12 # range\npBody.f[20:21] pBody.f[30]\nf[40]\n");
  EXPECT_EQ(s.object, "pBody");
  EXPECT_EQ(selected_faces(s, 100), (std::vector<Index>{1, 2, 3, 10, 11, 12, 20, 21, 30, 40}));
  EXPECT_EQ(s.ranges[3].line, 3);  // 10-12
}

TEST(PatchFile, RejectsBadTokensWithTheirLine) {
  EXPECT_EQ(error_of("1 2\nselect -r\n"),
            "p.txt:2: unknown token 'select': expected a face id (12), a range (12-40) or a Maya "
            "component (pBody.f[12:40])");
  EXPECT_EQ(error_of("5-3\n"), "p.txt:1: range '5-3' runs backwards");
  EXPECT_NE(error_of("-3\n").find("unknown token '-3'"), std::string::npos);
  EXPECT_EQ(
      error_of("a.f[1]\nb.f[2]\n"),
      "p.txt:2: names object 'b' but line 1 names 'a': one patch file selects faces of one mesh");
  EXPECT_EQ(error_of("1\n\n150\n"),
            "p.txt:3: face 150 is out of range (the bind has 100 faces, numbered 0 to 99)");
  EXPECT_EQ(error_of("# nothing\n"), "p.txt: selects no faces");
  EXPECT_NE(error_of("pBody.vtx[3]\n").find("unknown token"), std::string::npos);
}

}  // namespace
}  // namespace skinslide
