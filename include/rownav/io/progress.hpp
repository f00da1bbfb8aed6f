#pragma once
/// @file progress.hpp A progress line for long runs (simulation, batch evaluation).
#include <chrono>
#include <iostream>
#include <string>

namespace rownav::io {

/// On a terminal (stderr is a TTY, or force_tty) redraws one line
/// "\rlabel [#####.....] 42% 12.3/30.0 ETA 0:07" at most 10 times a second; otherwise (CI logs,
/// pipes) prints one plain line "label: 40% 12.0/30.0" at each 10 % step, so logs stay short.
class Progress {
 public:
  /// @param total amount of work (> 0; non-positive totals count as 1)
  Progress(std::string label, double total, std::ostream& out = std::cerr, bool force_tty = false);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Reports `done` units of work so far (clamped to [0, total]).
  void update(double done);
  /// Prints the final 100 % line (once; also called by the destructor).
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  void draw(double done, bool final_line);

  std::string label_;
  double total_;
  std::ostream& out_;
  bool tty_;
  bool finished_ = false;
  int last_step_ = -1;  // last 10 % step printed (plain mode)
  Clock::time_point start_, last_draw_;
  bool drawn_ = false;
};

}  // namespace rownav::io
