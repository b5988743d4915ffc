// What the CLI tells the user on stderr: per-frame lines in frame order, a TTY progress line.
#pragma once

#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

#include "core/stopwatch.h"

namespace skinslide::cli {

enum class Verbosity { Quiet, Normal, Verbose };

/// Collects per-frame messages from worker threads and prints them in frame order, so a log
/// reads the same whatever the thread count. On a terminal a `\r` progress bar stands for them
/// (-v prints them above it).
class Progress {
 public:
  Progress(size_t frame_count, Verbosity verbosity, bool is_terminal);
  /// Frame `index` finished; `lines` are printed (in frame order) unless quiet.
  void done(size_t index, std::vector<std::string> lines);
  /// Clears the progress line (before a final summary or an error).
  void finish();
  double elapsed_seconds() const;

 private:
  void draw_locked();
  size_t count_;
  Verbosity verbosity_;
  bool terminal_;
  std::mutex mutex_;
  std::vector<std::vector<std::string>> pending_;
  std::vector<char> finished_;
  size_t next_to_print_ = 0;
  size_t finished_count_ = 0;
  bool line_drawn_ = false;
  Clock::time_point start_;
};

}  // namespace skinslide::cli
