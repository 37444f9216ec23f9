#pragma once
/// @file
/// A node without LCM for the responders (runtime/tick_responder.hpp,
/// runtime/realtime_responder.hpp, runtime/status_reporter.hpp): the test
/// delivers messages by hand, or from a script run at every handle() and
/// drain(), and reads what was published. Subscriptions validate as
/// LcmNode's do (a rejected message never reaches the handler); ordering by
/// sequence number, run identity and checksums are LcmNode's own business
/// and tested with it.

#include <any>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "lagrange/channel_stats_t.hpp"
#include "transport/lcm_node.hpp"

namespace lagrange::testing {

class FakeNode {
 public:
  explicit FakeNode(std::string process_name) : process_name_(std::move(process_name)) {}

  template <class Msg>
  void subscribe(const std::string& channel, std::function<transport::Rejection(const Msg&)> validate,
                 std::function<void(const Msg&)> handle,
                 transport::LcmNode::Order = transport::LcmNode::Order::kNewestOnly) {
    handlers_[channel].push_back([this, validate, handle](const std::any& message) {
      const Msg& m = std::any_cast<const Msg&>(message);
      if (validate(m).empty())
        handle(m);
      else
        ++rejected_;
    });
  }

  template <class Msg>
  void publish(const std::string& channel, const Msg& msg) {
    published_[channel].emplace_back(msg);
  }

  /// Hands `msg` to every subscription of `channel`, as if it had arrived.
  template <class Msg>
  void deliver(const std::string& channel, const Msg& msg) {
    for (auto& handler : handlers_[channel]) handler(std::any(msg));
  }

  /// What the node published on `channel`, in order.
  template <class Msg>
  std::vector<Msg> published(const std::string& channel) const {
    std::vector<Msg> out;
    const auto it = published_.find(channel);
    if (it != published_.end())
      for (const std::any& m : it->second) out.push_back(std::any_cast<const Msg&>(m));
    return out;
  }

  /// Runs at every handle() and drain(): the test's traffic, one step per call.
  void onPoll(std::function<void()> script) { script_ = std::move(script); }
  bool handle(int /*timeout_ms*/) {
    poll();
    return true;
  }
  int drain(int /*max_messages*/ = 1000) {
    poll();
    return 0;
  }

  const std::string& processName() const { return process_name_; }
  std::vector<lagrange::channel_stats_t> channelStats() const { return {}; }
  std::string lastInvalid() const { return ""; }
  int64_t lastReceiveUtime() const { return 0; }
  int rejected() const { return rejected_; }
  int polls() const { return polls_; }

 private:
  void poll() {
    ++polls_;
    if (script_) script_();
  }

  std::string process_name_;
  std::map<std::string, std::vector<std::function<void(const std::any&)>>> handlers_;
  std::map<std::string, std::vector<std::any>> published_;
  std::function<void()> script_;
  int rejected_ = 0, polls_ = 0;
};

}  // namespace lagrange::testing
