#include "rownav/io/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rownav::io {
namespace {

std::string fixed1(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

/// "m:ss" (or "h:mm:ss"), "--:--" when unknown.
std::string clock_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--";
  const auto s = static_cast<long long>(std::llround(seconds));
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%lld:%02lld:%02lld", s / 3600, s / 60 % 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%lld:%02lld", s / 60, s % 60);
  return buf;
}

}  // namespace

Progress::Progress(std::string label, double total, std::ostream& out, bool force_tty)
    : label_(std::move(label)),
      total_(total > 0 && std::isfinite(total) ? total : 1.0),
      out_(out),
      tty_(force_tty || (&out == &std::cerr && ::isatty(::fileno(stderr)) != 0)),
      start_(Clock::now()),
      last_draw_(start_) {}

Progress::~Progress() {
  try {
    finish();
  } catch (...) {  // never throw from a destructor
  }
}

void Progress::update(double done) {
  if (finished_) return;
  done = std::clamp(std::isfinite(done) ? done : 0.0, 0.0, total_);
  if (tty_) {
    const auto now = Clock::now();
    if (drawn_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    draw(done, false);
    return;
  }
  const int step = static_cast<int>(std::floor(done / total_ * 10.0 + 1e-9));
  if (step <= last_step_ || step >= 10) return;  // 100 % is printed by finish()
  last_step_ = step;
  draw(done, false);
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  draw(total_, true);
}

void Progress::draw(double done, bool final_line) {
  drawn_ = true;
  const double frac = done / total_;
  const int percent = static_cast<int>(std::floor(frac * 100.0 + 1e-9));
  const std::string amounts = fixed1(done) + "/" + fixed1(total_);
  if (!tty_) {
    out_ << label_ << ": " << percent << "% " << amounts << '\n' << std::flush;
    return;
  }
  constexpr int kWidth = 20;
  const int filled = static_cast<int>(frac * kWidth);
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  const double eta = frac > 0 ? elapsed * (1.0 - frac) / frac : NAN;
  out_ << '\r' << label_ << " [" << std::string(filled, '#') << std::string(kWidth - filled, '.')
       << "] " << percent << "% " << amounts << " ETA " << clock_text(final_line ? 0.0 : eta)
       << (final_line ? "\n" : "") << std::flush;
}

}  // namespace rownav::io
