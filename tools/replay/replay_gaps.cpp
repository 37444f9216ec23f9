#include "tools/replay/replay_gaps.hpp"

#include "transport/channels.hpp"

namespace lagrange::tools::replay_log {

namespace {

std::string before(long long replayed) {
  return replayed == 0 ? "; no output before it was replayed"
                       : "; the " + std::to_string(replayed) + " outputs before it were replayed bit for bit";
}

std::string also(const std::string& clause) { return clause.empty() ? "" : "; " + clause; }

// "CONTROL_COMMAND tick 12 (the event at byte 345)"
std::string named(const Recorded& rec, const std::string& channel, int64_t tick) {
  const std::string where = whereIs(rec, channel, tick);
  return channel + " tick " + std::to_string(tick) + (where.empty() ? "" : " (" + where + ")");
}

}  // namespace

OutputSequence outputSequence(const std::string& channel, config::Mode mode) {
  return channel == transport::kPlantTruth || mode != config::Mode::kRealtime
             ? OutputSequence::kEveryTick
             : OutputSequence::kSequenceNumber;
}

void requireNoGap(const Recorded& rec, const std::string& channel, OutputSequence sequence,
                  const lagrange::header_t* previous, const lagrange::header_t& next, long long replayed) {
  const std::string component = transport::publisherOf(channel);
  if (sequence == OutputSequence::kEveryTick) {
    const int64_t expected = previous == nullptr ? 0 : previous->tick + 1;
    if (next.tick == expected) return;
    if (next.tick < expected)
      throw ReplayError("the log's " + named(rec, channel, next.tick) + " comes where tick " +
                        std::to_string(expected) + " was expected (the " + component +
                        "'s outputs run from tick 0, one per tick): the log is not as the run recorded it" +
                        before(replayed));
    throw ReplayError("the log lacks " + channel + " " + tickRange(expected, next.tick - 1) +
                      " (the next it holds is tick " + std::to_string(next.tick) + "; the " + component +
                      " answers every tick of this run, so the log has a gap there" +
                      also(whyLacking(rec, channel, expected, next.tick - 1)) + ")" + before(replayed));
  }
  const bool same_publisher = previous != nullptr && previous->publisher_pid == next.publisher_pid;
  const int64_t expected = same_publisher ? previous->seq + 1 : 1;
  if (next.seq == expected) return;
  if (next.seq < expected)
    throw ReplayError(
        "the log's " + named(rec, channel, next.tick) + " has sequence number " + std::to_string(next.seq) +
        " where " + std::to_string(expected) + " was expected (the " + component +
        " numbers its messages 1, 2, ...): the log is not as the run recorded it" + before(replayed));
  const int64_t missing = next.seq - expected;
  const int64_t from = same_publisher ? previous->tick + 1 : 0;
  throw ReplayError(
      "the log lacks " + std::to_string(missing) + " " + channel + " message" + (missing == 1 ? "" : "s") +
      " the " + component + " published " +
      (same_publisher ? "between tick " + std::to_string(previous->tick) + " and " : "before ") + "tick " +
      std::to_string(next.tick) + " (sequence number" + (missing == 1 ? " " : "s ") +
      std::to_string(expected) + (missing == 1 ? "" : " to " + std::to_string(next.seq - 1)) + "; the " +
      component + " numbers every message it publishes, so the log has a gap there" +
      (next.tick > from ? also(whyLacking(rec, channel, from, next.tick - 1)) : "") + ")" + before(replayed));
}

}  // namespace lagrange::tools::replay_log
