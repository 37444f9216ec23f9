#include "wiring/progress.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace lagrange::wiring {

ProgressDisplay::ProgressDisplay(double duration, bool quiet)
    : duration_(duration),
      quiet_(quiet),
      tty_(isatty(STDOUT_FILENO) != 0),
      next_draw_(std::chrono::steady_clock::now()) {}

void ProgressDisplay::update(double sim_time, double tracking_error) {
  if (!first_sample_) first_sample_ = std::make_pair(sim_time, std::chrono::steady_clock::now());
  sim_time_ = sim_time;
  if (std::isfinite(tracking_error)) error_ = tracking_error;
}

void ProgressDisplay::tick() {
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now < next_draw_) return;
  next_draw_ = now + (tty_ ? std::chrono::milliseconds(100) : std::chrono::milliseconds(2000));
  draw();
}

void ProgressDisplay::draw() {
  double rtf = 0.0;
  if (first_sample_) {
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - first_sample_->second).count();
    if (wall > 0.0) rtf = (sim_time_ - first_sample_->first) / wall;
  }
  const double fraction = duration_ > 0.0 ? std::min(1.0, sim_time_ / duration_) : 0.0;
  char err[32];
  if (error_ >= 0.0)
    std::snprintf(err, sizeof err, "%.2e rad", error_);
  else
    std::snprintf(err, sizeof err, "--");
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    std::string bar(filled, '#');
    bar += std::string(kWidth - filled, '.');
    std::printf("\r[%s] t = %7.2f / %.2f s  %5.1fx real time  |q~| = %s   ", bar.c_str(), sim_time_,
                duration_, rtf, err);
  } else {
    std::printf("progress: t = %.2f / %.2f s (%3.0f%%), %.1fx real time, |q~| = %s\n", sim_time_, duration_,
                100.0 * fraction, rtf, err);
  }
  std::fflush(stdout);
  drawn_ = true;
}

void ProgressDisplay::finish() {
  if (quiet_ || !drawn_) return;
  draw();
  if (tty_) std::printf("\n");
  std::fflush(stdout);
  drawn_ = false;
}

}  // namespace lagrange::wiring
