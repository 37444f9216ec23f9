#pragma once
/// @file
/// Progress of a run: on a terminal a bar redrawn in place (sim time,
/// real-time factor, current tracking error); otherwise a plain line every
/// 2 s, so logs of CI runs stay readable. The real-time factor is simulated
/// time over wall time since the first sample arrived.

#include <chrono>
#include <optional>
#include <utility>

namespace lagrange::wiring {

class ProgressDisplay {
 public:
  ProgressDisplay(double duration, bool quiet);
  void update(double sim_time, double tracking_error);  ///< latest values from the logger
  void tick();                                          ///< redraw if due
  void finish();                                        ///< end the line on a terminal

 private:
  void draw();
  double duration_;
  bool quiet_, tty_;
  double sim_time_ = 0.0, error_ = -1.0;
  bool drawn_ = false;
  // The real-time factor counts from the first sample, not from the launch:
  // starting the processes is not simulation.
  std::optional<std::pair<double, std::chrono::steady_clock::time_point>> first_sample_;
  std::chrono::steady_clock::time_point next_draw_;
};

}  // namespace lagrange::wiring
