#include "tools/run/session_handshake.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <iostream>

#include "lagrange/run_join_t.hpp"
#include "transport/channels.hpp"
#include "transport/checksum.hpp"
#include "transport/lcm_node.hpp"
#include "transport/messages.hpp"
#include "transport/safe_decode.hpp"
#include "util/error.hpp"
#include "util/terminal_text.hpp"

namespace lagrange::tools {

namespace {

using Clock = std::chrono::steady_clock;

std::string hostName() {
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) != 0) return "";
  return name;
}

lagrange::run_join_t toMessage(const JoinMessage& m) {
  lagrange::run_join_t out{};
  out.header = transport::makeHeader(0, 0.0);
  out.processes = m.processes;
  out.host = m.host;
  out.scenario_digest = m.scenario_digest;
  std::copy(m.nonce.begin(), m.nonce.end(), out.nonce);
  for (const Nonce& n : m.heard) out.heard.emplace_back(n.begin(), n.end());
  out.num_heard = static_cast<int32_t>(out.heard.size());
  out.agreed = m.agreed;
  return out;
}

// A decoded RUN_JOIN as the agreement takes it; nothing when it cannot be
// one (a key holder's malformed message: the MAC passed, the rest need not).
std::optional<JoinMessage> fromMessage(const lagrange::run_join_t& m) {
  if (m.num_heard < 0 || static_cast<std::size_t>(m.num_heard) > SessionAgreement::kMaxHeard ||
      m.heard.size() != static_cast<std::size_t>(m.num_heard) || m.processes.size() > 64 ||
      m.host.size() > 255)
    return std::nullopt;
  JoinMessage out;
  out.processes = m.processes;
  out.host = m.host;
  out.scenario_digest = m.scenario_digest;
  std::copy(m.nonce, m.nonce + 32, out.nonce.begin());
  for (const auto& row : m.heard) {
    if (row.size() != 32) return std::nullopt;
    Nonce n;
    std::copy(row.begin(), row.end(), n.begin());
    out.heard.push_back(n);
  }
  out.agreed = m.agreed;
  return out;
}

}  // namespace

int64_t runIdFromValue(const Nonce& value) {
  uint64_t id = 0;
  for (int i = 0; i < 8; ++i) id = (id << 8) | value[static_cast<std::size_t>(i)];
  return static_cast<int64_t>(id >> 1) | 1;
}

std::optional<AgreedRun> agreeWithOtherLaunchers(const HandshakeOptions& options,
                                                 const transport::MessageKey& shared_key,
                                                 const std::function<bool()>& stopped) {
  const auto start = Clock::now();
  const auto seconds = [&start] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  SessionAgreement agreement(options.processes, hostName(), options.scenario_digest,
                             transport::randomNonce());
  transport::LcmNode node("launcher", options.lcm_url, options.meeting_id);
  node.authenticate(shared_key);
  long long foreign = 0;  // authentic, but not a RUN_JOIN of this meeting
  node.subscribeRaw(transport::kRunJoin, [&](const lcm::ReceiveBuffer* rbuf, const std::string&) {
    lagrange::run_join_t m;
    std::optional<JoinMessage> join;
    if (transport::safeDecode(rbuf->data, rbuf->data_size, m) && transport::intact(m) &&
        m.header.run_id == options.meeting_id)
      join = fromMessage(m);
    if (!join) {
      ++foreign;
      return;
    }
    agreement.hear(*join, m.header.publisher_pid, seconds());
  });

  const std::string self = joinProcesses(options.processes);
  double next_send = 0.0, next_note = 5.0;
  std::optional<double> agreed_at;
  double conflict_since = -1.0;  // when the conflict now seen began (-1: none)
  while (!stopped()) {
    const double now = seconds();
    if (now >= next_send) {
      node.publish(transport::kRunJoin, toMessage(agreement.own(now)));
      next_send = now + 0.1;
    }
    node.handle(20);
    const SessionAgreement::State state = agreement.state(seconds());
    if (state == SessionAgreement::State::kConflict) {
      // Lasting: a launcher restarted on another host is heard beside its
      // predecessor for up to kLiveSeconds.
      if (conflict_since < 0.0) conflict_since = now;
      if (now - conflict_since > 1.5 * SessionAgreement::kLiveSeconds)
        throw BadInput("the launchers of this run cannot agree: " + agreement.conflict(seconds()));
    } else {
      conflict_since = -1.0;
    }
    if (state == SessionAgreement::State::kAgreed && !agreed_at) {
      agreed_at = now;
      next_send = now;  // say so at once
    }
    // Agreed: go on answering until every other launcher says it agreed too
    // (its last messages may have missed ours), at most a few seconds.
    if (agreed_at && (agreement.everyoneAgreed() || now - *agreed_at > 3.0)) {
      node.publish(transport::kRunJoin, toMessage(agreement.own(seconds())));  // a last word
      return AgreedRun{agreement.runValue(), agreement.members(seconds())};
    }
    if (now >= next_note && !options.quiet) {
      std::cerr << "lagrange run: " << self << ": waiting for "
                << util::terminalSafe(agreement.waitingFor(now)) << " on " << options.lcm_url << " ("
                << static_cast<int>(now) << " s of " << options.timeout << ", --join-timeout)\n";
      next_note = now + 5.0;
    }
    if (now > options.timeout) {
      std::string why = "no agreement with the other hosts' launchers within " +
                        std::to_string(static_cast<int>(options.timeout)) +
                        " s (--join-timeout): waited for " + agreement.waitingFor(now);
      const auto counters = node.counters().find(transport::kRunJoin);
      const long long unauthenticated =
          counters == node.counters().end()
              ? 0
              : counters->second
                    .rejected_by[static_cast<std::size_t>(transport::RejectReason::kUnauthenticated)];
      if (unauthenticated > 0)
        why += "; " + std::to_string(unauthenticated) +
               " RUN_JOIN datagrams failed the MAC (a launcher with another --key-file?)";
      if (const std::size_t n = agreement.unanswered(now); n > 0)
        why +=
            "; " + std::to_string(n) +
            " launchers were heard that never heard this one (a recording of another run re-sent, or a host "
            "that cannot reach this one: check the URL's TTL and the multicast route)";
      if (foreign > 0)
        why += "; " + std::to_string(foreign) + " RUN_JOIN messages of another meeting or malformed";
      throw RuntimeFault(why +
                         "; expected one `lagrange run --processes` per host with the same scenario, "
                         "--lcm-url, --key-file and --run-id (if any)");
    }
  }
  return std::nullopt;
}

}  // namespace lagrange::tools
