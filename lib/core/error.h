// The one exception type of skinslide: a kind (which decides the exit code) and a message.
#pragma once

#include <stdexcept>
#include <string>

namespace skinslide {

/// What went wrong, in the terms main() maps to exit codes (README "Exit codes").
enum class ErrorKind {
  Internal,  ///< a bug: an invariant did not hold (exit 1)
  Usage,     ///< the command line is wrong (exit 2)
  Input,     ///< an input file is unreadable or malformed (exit 3)
  Output,    ///< an output cannot be written (exit 4)
  Numeric,   ///< a solve failed or produced a non-finite number (exit 5)
};

class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  ErrorKind kind() const { return kind_; }

 private:
  ErrorKind kind_;
};

/// fn()'s result; an Error it throws comes out of the same kind, its message after "LABEL: " (a
/// frame's or a patch's name), so that the message says where.
template <class Fn>
auto labelled(const std::string& label, Fn&& fn) {
  try {
    return fn();
  } catch (const Error& e) {
    throw Error(e.kind(), label + ": " + e.what());
  }
}

/// Exit code for each kind: 0 ok, 1 internal, 2 usage, 3 bad input, 4 cannot write, 5 numeric.
int exit_code(ErrorKind kind);

/// "path:line: what" (line 0 = no line) for input errors.
std::string at(const std::string& path, long line, const std::string& what);

[[noreturn]] void throw_input(const std::string& path, long line, const std::string& what);

}  // namespace skinslide
