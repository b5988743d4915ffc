#include "core/error.h"

namespace skinslide {

int exit_code(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::Internal:
      return 1;
    case ErrorKind::Usage:
      return 2;
    case ErrorKind::Input:
      return 3;
    case ErrorKind::Output:
      return 4;
    case ErrorKind::Numeric:
      return 5;
  }
  return 1;
}

std::string at(const std::string& path, long line, const std::string& what) {
  if (line > 0) return path + ":" + std::to_string(line) + ": " + what;
  return path + ": " + what;
}

void throw_input(const std::string& path, long line, const std::string& what) {
  throw Error(ErrorKind::Input, at(path, line, what));
}

}  // namespace skinslide
