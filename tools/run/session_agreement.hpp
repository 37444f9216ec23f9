#pragma once
/// @file
/// How the launchers of a run spread over hosts (`lagrange run --processes`)
/// agree on a value fresh for this run before any of its processes starts
/// (docs/reliability.md "Threat model"). The processes then sign with a key
/// derived from the shared key file and that value
/// (transport::deriveRunKey), so traffic recorded from another run under the
/// same key file -- a colleague's capture, yesterday's run -- fails their
/// MAC, whatever run id it carries.
///
/// The protocol, over RUN_JOIN messages signed with the shared key:
/// - each launcher draws 32 random bytes (its nonce) and re-sends, until the
///   run starts, what it runs, the scenario's digest, its nonce and the
///   nonces of every other launcher it has heard;
/// - a launcher counts another as *live* only when that one's message lists
///   its own nonce: the nonce is fresh, so the message was made after this
///   launcher started, by a holder of the key -- not a recording. A recorded
///   RUN_JOIN of another run never lists it, and is never counted;
/// - the run is agreed when the live launchers and this one start every
///   process of the run exactly once, run the same scenario, and each live
///   one lists every other's nonce: then all of them derive the same value,
///   SHA-256 of the members' processes and nonces.
/// Pure: no LCM, no clock (the caller passes the time), so that the tests
/// drive every case -- a replayed launcher, a conflict, a lost message.

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace lagrange::tools {

using Nonce = std::array<uint8_t, 32>;

/// What one launcher says in a RUN_JOIN (lagrange/run_join_t.hpp, without the header).
struct JoinMessage {
  std::string processes;  ///< comma-separated, in kProcesses' order
  std::string host;
  int64_t scenario_digest = 0;
  Nonce nonce{};
  std::vector<Nonce> heard;
  bool agreed = false;
};

class SessionAgreement {
 public:
  /// A launcher heard within this many seconds is still there (they re-send
  /// every 0.1 s); one silent for longer has stopped and no longer counts.
  static constexpr double kLiveSeconds = 1.0;
  /// Launchers remembered, and nonces listed in a message, at most: a
  /// recording of up to 64 runs' launchers re-sent all at once still leaves
  /// room for this run's (an 8 kB message); more is a flood, which the MAC
  /// cannot stop either, and bounded: the longest-silent one goes first.
  static constexpr std::size_t kMaxPeers = 256;
  static constexpr std::size_t kMaxHeard = kMaxPeers;

  /// @param processes what this launcher starts (a subset of kProcesses).
  SessionAgreement(std::vector<std::string> processes, std::string host, int64_t scenario_digest,
                   const Nonce& nonce);

  /// A RUN_JOIN heard at time `now` [s] from the launcher with `pid`
  /// (authenticated by the caller). This launcher's own is ignored.
  void hear(const JoinMessage& m, int32_t pid, double now);

  /// What this launcher says now.
  JoinMessage own(double now);

  enum class State {
    kWaiting,   ///< not every process of the run has a live launcher yet
    kAgreed,    ///< runValue() is the run's
    kConflict,  ///< two live launchers start one process, or run different scenarios
  };
  /// Once kAgreed, the agreement is settled: the members and the value stay
  /// what they were, though a member falls silent (it has started its
  /// processes) -- every member derived the value from the same members.
  State state(double now);
  /// kConflict: what conflicts, naming hosts and pids.
  std::string conflict(double now) const;
  /// kWaiting: which processes lack a launcher, and what was heard instead.
  std::string waitingFor(double now) const;
  /// kAgreed: the run's value, the same at every member.
  Nonce runValue() const;
  /// kAgreed, and every member has said it agreed: no one needs this
  /// launcher's messages any more.
  bool everyoneAgreed() const;
  /// The live launchers (kAgreed: the members) besides this one, e.g.
  /// "logger,controller on hostB (pid 4242)".
  std::vector<std::string> members(double now) const;
  /// Launchers heard that never listed this one's nonce (a recording, or a
  /// launcher that cannot hear this one).
  std::size_t unanswered(double now) const;

 private:
  struct Peer {
    JoinMessage said;  ///< the first message's identity, the heard nonces merged
    int32_t pid = 0;
    double last_heard = 0.0;
  };
  bool lists(const JoinMessage& m, const Nonce& nonce) const;
  bool live(const Peer& p, double now) const;
  std::vector<const Peer*> livePeers(double now) const;

  std::vector<std::string> processes_;
  std::string own_processes_;
  std::string host_;
  int64_t digest_;
  Nonce nonce_;
  std::map<Nonce, Peer> peers_;
  std::vector<Nonce> settled_;  ///< kAgreed: the other members' nonces
  bool agreed_ = false;
  Nonce value_{};
};

/// "a,b" in kProcesses' order, for messages and for the run value.
std::string joinProcesses(const std::vector<std::string>& processes);

}  // namespace lagrange::tools
