#include "controller/chain_state_buffer.hpp"

namespace lagrange::controller {

void ChainStateBuffer::put(int64_t tick, const Eigen::MatrixXd& xi) {
  if (tick < oldest_wanted_ || states_.count(tick) > 0) return;
  states_.emplace(tick, xi);
  if (states_.size() > kCapacity) states_.erase(std::prev(states_.end()));
}

std::optional<Eigen::MatrixXd> ChainStateBuffer::take(int64_t tick) {
  oldest_wanted_ = std::max(oldest_wanted_, tick);
  states_.erase(states_.begin(), states_.lower_bound(oldest_wanted_));
  const auto it = states_.find(tick);
  if (it == states_.end()) return std::nullopt;
  return it->second;  // kept: a re-sent position k is answered the same way
}

}  // namespace lagrange::controller
