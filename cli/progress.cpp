#include "progress.h"

namespace skinslide::cli {

Progress::Progress(size_t frame_count, Verbosity verbosity, bool is_terminal)
    : count_(frame_count),
      verbosity_(verbosity),
      terminal_(is_terminal && verbosity != Verbosity::Quiet),
      pending_(frame_count),
      finished_(frame_count, 0),
      start_(Clock::now()) {}

double Progress::elapsed_seconds() const { return seconds_since(start_); }

void Progress::done(size_t index, std::vector<std::string> lines) {
  std::lock_guard<std::mutex> lock(mutex_);
  pending_[index] = std::move(lines);
  finished_[index] = 1;
  ++finished_count_;
  if (line_drawn_) {
    std::fputs("\r\033[K", stderr);
    line_drawn_ = false;
  }
  // On a terminal the bar stands for the per-frame lines (README "Usage"); -v prints them above.
  const bool print =
      verbosity_ == Verbosity::Verbose || (verbosity_ == Verbosity::Normal && !terminal_);
  while (next_to_print_ < count_ && finished_[next_to_print_]) {
    if (print)
      for (const std::string& l : pending_[next_to_print_]) std::fprintf(stderr, "%s\n", l.c_str());
    pending_[next_to_print_].clear();
    ++next_to_print_;
  }
  draw_locked();
}

void Progress::draw_locked() {
  if (!terminal_ || finished_count_ == count_) return;
  const double t = elapsed_seconds();
  const double fps = t > 0 ? static_cast<double>(finished_count_) / t : 0.0;
  const double left = fps > 0 ? static_cast<double>(count_ - finished_count_) / fps : 0.0;
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(kWidth * finished_count_ / count_);
  std::string bar(filled, '#');
  bar.append(kWidth - filled, '.');
  std::fprintf(stderr, "[%s] %zu/%zu frames  %.1f frames/s  %.0f s left", bar.c_str(),
               finished_count_, count_, fps, left);
  std::fflush(stderr);
  line_drawn_ = true;
}

void Progress::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (line_drawn_) std::fputs("\r\033[K", stderr);
  line_drawn_ = false;
}

}  // namespace skinslide::cli
