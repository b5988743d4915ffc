// Shared by the glTF tests: temporary folders, the Khronos validator, the JSON comparison.
#pragma once

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "helpers/shared_data.h"
#include "helpers/temp_dir.h"

namespace skinslide::testing {

/// Standard base64 (with padding), for data-URI buffers written by the tests.
inline std::string base64(const std::vector<unsigned char>& d) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string s;
  for (size_t i = 0; i < d.size(); i += 3) {
    unsigned v = d[i] << 16;
    if (i + 1 < d.size()) v |= d[i + 1] << 8;
    if (i + 2 < d.size()) v |= d[i + 2];
    s += k[(v >> 18) & 63];
    s += k[(v >> 12) & 63];
    s += i + 1 < d.size() ? k[(v >> 6) & 63] : '=';
    s += i + 2 < d.size() ? k[v & 63] : '=';
  }
  return s;
}

/// ../shared/data/gltf/NAME; a test reading it starts with SKINSLIDE_REQUIRE_GLTF(NAME, ...).
inline std::string shared_gltf(const std::string& name) {
  return ::skinslide::test::shared_dir() + "/data/gltf/" + name;
}

inline std::vector<std::string> shared_gltf_relatives(const std::vector<std::string>& names) {
  std::vector<std::string> r;
  for (const std::string& n : names) r.push_back("data/gltf/" + n);
  return r;
}

/// SKINSLIDE_REQUIRE_GLTF("Fox.glb", ...): SKINSLIDE_REQUIRE_SHARED for files of data/gltf.
#define SKINSLIDE_REQUIRE_GLTF(...)                             \
  SKINSLIDE_SKIP_IF_MISSING_(::skinslide::test::missing_shared( \
      ::skinslide::testing::shared_gltf_relatives({__VA_ARGS__})))

/// A fresh, empty folder named after the running test, in the test process's scratch folder
/// (removed when the process exits: helpers/temp_dir.h).
inline std::filesystem::path temp_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  auto dir = ::skinslide::test::process_temp_dir() /
             (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

struct CommandResult {
  int status = -1;  ///< exit status, -1 when it could not be run
  std::string output;
};

inline CommandResult run_command(const std::string& command) {
  CommandResult r;
  FILE* p = popen((command + " 2>&1").c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  const int s = pclose(p);
  r.status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
  return r;
}

inline std::string quoted(const std::string& s) { return "'" + s + "'"; }

/// Runs the Khronos glTF validator (scripts/gltf_validate.sh, which installs it when missing) on
/// `files`. Fails the test on any validation error; skips it, saying why, only when the
/// validator cannot be installed or run (no node, npm unreachable).
#define SKINSLIDE_EXPECT_VALID_GLTF(files)                                                  \
  do {                                                                                      \
    std::string cmd_ = "bash " SKINSLIDE_SOURCE_DIR "/scripts/gltf_validate.sh";            \
    for (const std::string& f_ : (files)) cmd_ += " " + ::skinslide::testing::quoted(f_);   \
    const auto r_ = ::skinslide::testing::run_command(cmd_);                                \
    if (r_.status == 2 || r_.status == -1)                                                  \
      GTEST_SKIP() << "the Khronos glTF validator is unavailable (node/npm unreachable):\n" \
                   << r_.output;                                                            \
    EXPECT_EQ(r_.status, 0) << r_.output;                                                   \
  } while (0)

/// tests/io/gltf/gltf_compare.py: same JSON apart from schema defaults (and min/max of `edited`
/// accessors), and, when nothing is edited, the same buffer bytes. Returns its report.
inline CommandResult compare_gltf(const std::string& a, const std::string& b,
                                  const std::vector<int>& edited = {}) {
  std::string cmd = "python3 " SKINSLIDE_SOURCE_DIR "/tests/io/gltf/gltf_compare.py " + quoted(a) +
                    " " + quoted(b);
  if (!edited.empty()) {
    cmd += " --edited ";
    for (size_t i = 0; i < edited.size(); ++i) cmd += (i ? "," : "") + std::to_string(edited[i]);
  }
  return run_command(cmd);
}

}  // namespace skinslide::testing
