#include "transport/lcm_node.hpp"

#include <spdlog/spdlog.h>

#include <cerrno>

namespace lagrange::transport {

LcmNode::LcmNode(const std::string& process_name, const std::string& url)
    : process_name_(process_name), lcm_(url) {
  if (!lcm_.good())
    throw std::runtime_error(process_name + ": cannot open LCM at '" + url +
                             "'; expected a working LCM URL such as udpm://239.255.76.67:7667?ttl=0 "
                             "and a network interface with multicast enabled");
}

void LcmNode::subscribeRaw(const std::string& channel_regex,
                           std::function<void(const lcm::ReceiveBuffer*, const std::string&)> handle) {
  handlers_.push_back(std::make_unique<RawHandler>(RawHandler{std::move(handle)}));
  lcm::Subscription* sub = lcm_.subscribe(channel_regex, &RawHandler::onMessage, handlers_.back().get());
  sub->setQueueCapacity(kQueueCapacity);
}

bool LcmNode::handle(int timeout_ms) {
  if (lcm_.handleTimeout(timeout_ms) >= 0) return true;
  return errno == EINTR;  // a signal interrupted the wait: not an LCM failure
}

int LcmNode::drain(int max_messages) {
  int handled = 0;
  while (handled < max_messages && lcm_.handleTimeout(0) > 0) ++handled;
  return handled;
}

void LcmNode::reject(const std::string& channel, const std::string& reason) {
  counters_[channel].rejected++;
  if (reported_.insert(channel + "\n" + reason).second)
    spdlog::warn("{}: rejected a message on {}: {} (further ones of this kind are counted, not logged)",
                 process_name_, channel, reason);
}

void LcmNode::noteError(const std::string& channel, const std::string& what) {
  if (reported_.insert(channel + "\n" + what).second)
    spdlog::error("{}: {} on {}", process_name_, what, channel);
}

std::vector<lagrange::channel_stats_t> LcmNode::channelStats() const {
  std::vector<lagrange::channel_stats_t> out;
  for (const auto& [channel, c] : counters_) {
    lagrange::channel_stats_t s;
    s.channel = channel;
    s.published = c.published;
    s.received = c.received;
    s.rejected = c.rejected;
    out.push_back(s);
  }
  return out;
}

}  // namespace lagrange::transport
