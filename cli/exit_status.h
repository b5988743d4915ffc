// How a command ends (README "Exit codes"): the one place where an error becomes its message on
// stderr and its exit code, for `skinslide` (main.cpp), `skinslide join` (join.cpp) and
// `skinslide compare` (compare.cpp).
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace skinslide::cli {

/// The exit of a command line CLI11 refused: --help and --version print and exit 0; anything
/// else prints "<program>: error: <what>" and "Run with --help for the options." and exits 2,
/// <what> naming a misspelt option and the nearest one when there is one (check_unknown_options).
int parse_error_exit(const CLI::App& app, const CLI::ParseError& error, const char* program);

/// Runs `work` (the command's work once its options are read) and returns its exit code. An
/// error it throws is printed as "<program>: error: <what>" and exits with its kind's code;
/// running out of memory, or any other exception, exits 1 (internal).
int exit_status(const char* program, const std::function<int()>& work);

}  // namespace skinslide::cli
