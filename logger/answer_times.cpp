#include "logger/answer_times.hpp"

#include <algorithm>
#include <utility>

namespace lagrange::logger {

namespace {

// Questions kept waiting at most: a stray far-future tick must not grow the
// logger without bound (the oldest are dropped, never said slow).
constexpr size_t kMaxWaiting = 4096;

}  // namespace

AnswerTimes::AnswerTimes(std::vector<Answerer> answerers, double threshold) : threshold_(threshold) {
  for (Answerer& a : answerers) {
    Record r;
    r.who = std::move(a);
    records_.push_back(std::move(r));
  }
}

void AnswerTimes::arrived(const std::string& channel, int64_t tick, double t) {
  for (Record& r : records_) {
    if (channel == r.who.question) {
      // Re-sent questions, and ones already answered or passed by a newer
      // answer (realtime answers the newest), are not waits.
      if (tick <= r.answered_tick || r.asked.count(tick)) continue;
      r.asked.emplace(tick, t);
      if (r.asked.size() > kMaxWaiting) r.asked.erase(r.asked.begin());
    } else if (channel == r.who.answer) {
      const auto it = r.asked.find(tick - r.who.tick_offset);
      if (it == r.asked.end()) continue;  // a copy, or an answer to nothing heard
      const double took = t - it->second;
      r.times.add(took);
      if (took > r.worst || r.worst_tick < 0) {
        r.worst = took;
        r.worst_tick = it->first;
      }
      if (took > threshold_) ++r.slow;
      r.answered_tick = std::max(r.answered_tick, it->first);
      r.asked.erase(r.asked.begin(), std::next(it));  // older ones were passed by
    }
  }
}

std::vector<AnswerTimes::Slow> AnswerTimes::newlySlow(double now, double repeat_every) {
  std::vector<Slow> out;
  for (Record& r : records_) {
    if (r.asked.empty()) continue;
    const auto& [tick, since] = *r.asked.begin();  // the oldest question still waiting
    const double waited = now - since;
    if (waited <= threshold_ || tick <= r.said_tick || now - r.said_at < repeat_every) continue;
    r.said_tick = tick;
    r.said_at = now;
    out.push_back({r.who.name, r.who.program, tick, waited});
  }
  return out;
}

nlohmann::json AnswerTimes::summary() const {
  nlohmann::json j;
  j["threshold"] = threshold_;
  for (const Record& r : records_) {
    nlohmann::json a;
    a["program"] = r.who.program;
    const bool none = r.times.count() == 0;
    a["answered"] = r.times.count();
    a["median"] = none ? nlohmann::json() : nlohmann::json(r.times.percentiles().p50);
    a["worst"] = none ? nlohmann::json() : nlohmann::json(r.worst);
    a["worst_tick"] = none ? nlohmann::json() : nlohmann::json(r.worst_tick);
    a["slow"] = r.slow;
    j[r.who.name] = std::move(a);
  }
  return j;
}

}  // namespace lagrange::logger
