#include "io/run_inputs.h"

#include <filesystem>

#include <gtest/gtest.h>

#include <sys/stat.h>

#include "core/error.h"
#include "helpers/meshes.h"
#include "helpers/temp_dir.h"
#include "io/atomic_write.h"

namespace skinslide {

// A file read inside a scope is an input under any of its names (a symlink, a hard link, another
// spelling): AtomicFile refuses to replace it and the file keeps its bytes; after the last scope
// ends it may be written again (a Python session writes what an earlier call read).
TEST(RunInputs, AFileReadInARunIsNeverReplacedByItsOutputs) {
  namespace fs = std::filesystem;
  const std::string dir = test::temp_dir("run_inputs");
  const std::string path = dir + "/patch.txt";
  write_file_atomic(path, "0 1 2\n");
  fs::create_symlink(path, dir + "/link.txt");
  fs::create_hard_link(path, dir + "/hard.txt");
  {
    const InputScope run;
    {
      const InputScope nested;
      EXPECT_EQ(read_file(path), "0 1 2\n");
    }
    for (const std::string& name :
         {path, dir + "/link.txt", dir + "/hard.txt", dir + "/./patch.txt"}) {
      EXPECT_EQ(noted_input(name), path) << name;
      try {
        write_file_atomic(name, "replaced");
        ADD_FAILURE() << name << " was replaced";
      } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Output);
        EXPECT_NE(std::string(e.what()).find("it is an input of this run (" + path + ")"),
                  std::string::npos)
            << e.what();
      }
    }
    EXPECT_EQ(read_file(path), "0 1 2\n");
    EXPECT_FALSE(noted_input(dir + "/other.txt"));
    write_file_atomic(dir + "/other.txt", "an output");
  }
  EXPECT_FALSE(noted_input(path));
  write_file_atomic(path, "replaced");
  EXPECT_EQ(read_file(path), "replaced");
  // Outside any scope nothing is noted.
  EXPECT_EQ(read_file(path), "replaced");
  EXPECT_FALSE(noted_input(path));
}

// rename() would turn a pipe or a device into a plain file: refused, the pipe kept.
TEST(RunInputs, APipeIsNeverReplacedByAFile) {
  namespace fs = std::filesystem;
  const std::string fifo = test::temp_dir("run_inputs_fifo") + "/report.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THROW(write_file_atomic(fifo, "{}"), Error);
  EXPECT_TRUE(fs::is_fifo(fifo));
}

}  // namespace skinslide
