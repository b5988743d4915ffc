// Runs a shell command and captures its output, for tests that call independent tools.
#pragma once

#include <array>
#include <cstdio>
#include <string>

#include <sys/wait.h>

namespace skinslide::test {

struct RunResult {
  int exit_code = -1;  ///< -1 when the command could not be started or did not exit normally
  std::string output;  ///< stdout and stderr
};

inline RunResult run(const std::string& command) {
  RunResult r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  while (size_t n = fread(buf.data(), 1, buf.size(), pipe)) r.output.append(buf.data(), n);
  const int status = pclose(pipe);
  if (status != -1 && WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  return r;
}

}  // namespace skinslide::test
