#include "transport/fault_injector.hpp"

#include <algorithm>

namespace lagrange::transport {

namespace {
// A held datagram goes out after the next one on its channel, or after this
// long if none follows (the last message of a run must not be lost).
constexpr auto kMaxHold = std::chrono::milliseconds(20);
}  // namespace

FaultInjector::FaultInjector(lcm::LCM& lcm, std::map<std::string, FaultRule> rules, uint64_t seed)
    : lcm_(lcm), rules_(std::move(rules)), rng_(seed), worker_([this] { run(); }) {}

FaultInjector::~FaultInjector() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

const FaultRule* FaultInjector::rulesFor(const std::string& channel) const {
  auto it = rules_.find(channel);
  if (it == rules_.end()) it = rules_.find("all");
  return it == rules_.end() || !it->second.any() ? nullptr : &it->second;
}

int FaultInjector::send(const std::string& channel, const std::vector<uint8_t>& bytes) {
  return lcm_.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
}

int FaultInjector::publish(const std::string& channel, std::vector<uint8_t> bytes) {
  const FaultRule* rules = rulesFor(channel);
  if (rules == nullptr) return send(channel, bytes);
  std::unique_lock<std::mutex> lock(mutex_);
  InjectedCounts& count = counts_[channel];
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Every draw is made for every datagram, so one fault's rate does not
  // shift the random sequence of another.
  const bool drop = unit(rng_) < rules->drop, corrupt = unit(rng_) < rules->corrupt,
             duplicate = unit(rng_) < rules->duplicate, reorder = unit(rng_) < rules->reorder;
  const double delay = rules->delay + rules->delay_jitter * unit(rng_);
  const size_t flip_at = static_cast<size_t>(unit(rng_) * static_cast<double>(bytes.size()));
  const auto flip_bits = static_cast<uint8_t>(1u + static_cast<unsigned>(unit(rng_) * 255.0));

  // What was held for reordering goes out after this datagram.
  std::optional<std::vector<uint8_t>> release;
  if (auto h = held_.find(channel); h != held_.end()) {
    release = std::move(h->second);
    held_.erase(h);
  }
  int rc = 0;
  if (drop) {
    ++count.dropped;
  } else {
    if (corrupt && !bytes.empty()) {
      bytes[std::min(flip_at, bytes.size() - 1)] ^= flip_bits;
      ++count.corrupted;
    }
    const int copies = duplicate ? 2 : 1;
    count.duplicated += copies - 1;
    if (reorder && !release) {
      held_[channel] = bytes;  // released by the next datagram, or by the worker after kMaxHold
      ++count.reordered;
      schedule({Clock::now() + kMaxHold, channel, {}});
      if (copies == 2) rc = send(channel, bytes);
    } else if (delay > 0.0) {
      ++count.delayed;
      for (int i = 0; i < copies; ++i)
        schedule(
            {Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(delay)),
             channel, bytes});
    } else {
      for (int i = 0; i < copies; ++i) rc = send(channel, bytes);
    }
  }
  if (release) send(channel, *release);
  return rc;
}

void FaultInjector::schedule(Pending p) {
  pending_.push_back(std::move(p));
  wake_.notify_all();
}

void FaultInjector::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    const auto now = Clock::now();
    // Due datagrams out; an empty one is the deadline of a held datagram.
    for (auto it = pending_.begin(); it != pending_.end();) {
      if (it->due > now && !stopping_) {
        ++it;
        continue;
      }
      if (it->bytes.empty()) {
        if (auto h = held_.find(it->channel); h != held_.end()) {
          send(it->channel, h->second);
          held_.erase(h);
        }
      } else {
        send(it->channel, it->bytes);
      }
      it = pending_.erase(it);
    }
    if (stopping_) {
      for (auto& [channel, bytes] : held_) send(channel, bytes);
      held_.clear();
      return;
    }
    if (pending_.empty()) {
      wake_.wait(lock);
    } else {
      // A copy: waiting releases the lock, and a publish may then grow pending_.
      const Clock::time_point next =
          std::min_element(pending_.begin(), pending_.end(), [](const Pending& a, const Pending& b) {
            return a.due < b.due;
          })->due;
      wake_.wait_until(lock, next);
    }
  }
}

InjectedCounts FaultInjector::counts(const std::string& channel) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = counts_.find(channel);
  return it == counts_.end() ? InjectedCounts{} : it->second;
}

}  // namespace lagrange::transport
