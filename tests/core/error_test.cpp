#include "core/error.h"

#include <gtest/gtest.h>

namespace skinslide {

TEST(Error, EachKindHasItsDocumentedExitCode) {
  EXPECT_EQ(exit_code(ErrorKind::Internal), 1);
  EXPECT_EQ(exit_code(ErrorKind::Usage), 2);
  EXPECT_EQ(exit_code(ErrorKind::Input), 3);
  EXPECT_EQ(exit_code(ErrorKind::Output), 4);
  EXPECT_EQ(exit_code(ErrorKind::Numeric), 5);
}

TEST(Error, InputMessagesNameFileAndLine) {
  EXPECT_EQ(at("bind.obj", 118, "face has 2 vertices"), "bind.obj:118: face has 2 vertices");
  EXPECT_EQ(at("bind.obj", 0, "no vertices"), "bind.obj: no vertices");
  try {
    throw_input("p.txt", 3, "bad");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_STREQ(e.what(), "p.txt:3: bad");
  }
}

}  // namespace skinslide
