#include "io/file_key.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "helpers/temp_dir.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

// One file under any name is one key: another spelling, a link, a hard link.
TEST(FileKeys, OneFileUnderEveryName) {
  const test::TempDir dir("file_key_names");
  fs::create_directories(dir.path() / "sub");
  std::ofstream(dir / "f.obj") << "v 0 0 0\n";
  fs::create_symlink(dir / "f.obj", dir / "link.obj");
  fs::create_hard_link(dir / "f.obj", dir / "hard.obj");
  FileKeys keys;
  const FileKey f = keys.key(dir / "f.obj", ErrorKind::Input);
  EXPECT_TRUE(f.rest.empty());
  EXPECT_EQ(keys.key(dir / "sub/../f.obj", ErrorKind::Input), f);
  EXPECT_EQ(keys.key(dir / "link.obj", ErrorKind::Input), f);
  EXPECT_EQ(keys.key(dir / "hard.obj", ErrorKind::Input), f);
  EXPECT_NE(keys.key(dir / "sub", ErrorKind::Input), f);
}

// A path not made yet is named by its nearest folder there and the rest: equal for one name in
// two spellings, different for two names, never equal to an existing file.
TEST(FileKeys, FilesNotMadeYetByTheirFolder) {
  const test::TempDir dir("file_key_missing");
  fs::create_directories(dir.path() / "sub");
  std::ofstream(dir / "f.obj") << "v 0 0 0\n";
  FileKeys keys;
  const FileKey a = keys.key(dir / "out/a.obj", ErrorKind::Output);
  EXPECT_EQ(a.rest, "out/a.obj");
  EXPECT_EQ(keys.key(dir / "sub/../out/a.obj", ErrorKind::Output), a);
  EXPECT_NE(keys.key(dir / "out/b.obj", ErrorKind::Output), a);
  EXPECT_NE(keys.key(dir / "out/a.obj", ErrorKind::Output),
            keys.key(dir / "f.obj", ErrorKind::Input));
  // Below a file: not made yet either (writing it fails later, with the writer's message).
  EXPECT_EQ(keys.key(dir / "f.obj/x.obj", ErrorKind::Output).rest, "x.obj");
}

// A path the system cannot look at (here a loop of links; for a user, a folder it may not
// enter) has no key: an error naming it, never "the same file" as another such path.
TEST(FileKeys, APathThatCannotBeLookedAtIsAnError) {
  const test::TempDir dir("file_key_loop");
  fs::create_symlink(dir / "loop", dir / "loop");
  FileKeys keys;
  try {
    keys.key(dir / "loop/bind.obj", ErrorKind::Input);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_EQ(std::string(e.what()),
              dir / "loop/bind.obj" + ": cannot read: Too many levels of symbolic links");
  }
  try {
    keys.key(dir / "loop/out/f.obj", ErrorKind::Output);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Output);
    EXPECT_NE(std::string(e.what()).find(": cannot write: Too many levels"), std::string::npos);
  }
}

}  // namespace
}  // namespace skinslide
