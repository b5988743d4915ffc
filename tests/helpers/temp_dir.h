// Scratch folders of the tests, under the system's temporary folder ($TMPDIR, else /tmp), all
// removed: a TempDir at its scope's end, a temp_dir() folder when the test process exits.
#pragma once

#include <filesystem>
#include <string>

#include <unistd.h>

namespace skinslide::test {

/// A fresh folder, removed with its contents at scope end. The process id in its name keeps two
/// test runs on one machine out of each other's folders.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("skinslide_test_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string operator/(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// The test process's own scratch folder, made on first use and removed when the process exits
/// normally (a static TempDir; ctest runs each test in a process of its own). Tests that need a
/// folder for the whole test take one inside it (temp_dir), so that none is left in /tmp.
inline const std::filesystem::path& process_temp_dir() {
  static const TempDir root("process");
  return root.path();
}

}  // namespace skinslide::test
