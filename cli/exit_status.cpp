#include "exit_status.h"

#include <cstdio>
#include <new>
#include <string>

#include "config_keys.h"
#include "core/error.h"

namespace skinslide::cli {

int parse_error_exit(const CLI::App& app, const CLI::ParseError& error, const char* program) {
  if (error.get_exit_code() == 0) return app.exit(error);
  std::string what = error.what();
  // A misspelt option is what went wrong, whatever CLI11 found missing or extra after it.
  try {
    check_unknown_options(app);
  } catch (const CLI::ParseError& unknown) {
    what = unknown.what();
  }
  std::fprintf(stderr, "%s: error: %s\nRun with --help for the options.\n", program, what.c_str());
  return exit_code(ErrorKind::Usage);
}

int exit_status(const char* program, const std::function<int()>& work) {
  try {
    return work();
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    return exit_code(e.kind());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "%s: error: out of memory\n", program);
    return exit_code(ErrorKind::Internal);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error: %s\n", program, e.what());
    return exit_code(ErrorKind::Internal);
  }
}

}  // namespace skinslide::cli
