#pragma once
// A progress line for long work, on standard error when it is a terminal
// (quiet otherwise: a log or a pipe gets no carriage returns). Redrawn at
// most every kEvery, cleared when done.

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace cairn::cli {

class Progress {
 public:
  /// `what` starts the line ("cairn simulate").
  explicit Progress(std::string what)
      : what_(std::move(what)), on_(::isatty(::fileno(stderr)) == 1) {}
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  ~Progress() { Done(); }

  /// Shows `state` ("step 1/3, time step 1200/5000") if the last redraw is
  /// older than kEvery.
  void Show(const std::string& state) {
    if (!on_) return;
    const auto now = Clock::now();
    if (shown_ && now - last_ < kEvery) return;
    last_ = now;
    shown_ = true;
    std::fprintf(stderr, "\r%s: %s\033[K", what_.c_str(), state.c_str());
    std::fflush(stderr);
  }
  /// Clears the line.
  void Done() {
    if (!on_ || !shown_) return;
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
    shown_ = false;
  }

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kEvery{250};
  std::string what_;
  bool on_ = false, shown_ = false;
  Clock::time_point last_{};
};

}  // namespace cairn::cli
