#pragma once
/// @file
/// The actuator chain states the controller has heard, keyed by the position
/// tick each belongs to (ACTUATOR_STATE k carries xi at t_{k+1}).
///
/// Lockstep answers position k only with the state of t_k; keeping states by
/// tick means a stray message with a far-future tick (another run, a replay)
/// occupies one slot and is never used, instead of replacing the state the
/// run is waiting for. Bounded: at most kCapacity states, older ticks than the
/// one last asked for are dropped, and when full the farthest future goes.
/// Pure: no I/O.

#include <Eigen/Dense>
#include <cstdint>
#include <map>
#include <optional>

namespace lagrange::controller {

class ChainStateBuffer {
 public:
  static constexpr size_t kCapacity = 256;

  /// Empty: every tick's state comes from a message (e.g. PLANT_MOTOR samples).
  ChainStateBuffer() = default;
  /// xi(0): the configured initial chain state belongs to position tick 0.
  explicit ChainStateBuffer(const Eigen::MatrixXd& initial) { states_[0] = initial; }

  /// The state of position tick `tick` (an ACTUATOR_STATE of tick - 1).
  /// Ignored when older than the last tick asked for or already present.
  void put(int64_t tick, const Eigen::MatrixXd& xi);

  /// The state for position tick `tick`, if heard; forgets older ones.
  std::optional<Eigen::MatrixXd> take(int64_t tick);

  size_t size() const { return states_.size(); }

 private:
  std::map<int64_t, Eigen::MatrixXd> states_;
  int64_t oldest_wanted_ = 0;
};

}  // namespace lagrange::controller
