#include "tools/run/session_agreement.hpp"

#include <algorithm>
#include <set>
#include <sstream>

#include "tools/run/run_command.hpp"
#include "transport/message_auth.hpp"

namespace lagrange::tools {

std::string joinProcesses(const std::vector<std::string>& processes) {
  std::string out;
  for (const std::string& p : kProcesses)
    if (std::find(processes.begin(), processes.end(), p) != processes.end())
      out += (out.empty() ? "" : ",") + p;
  return out;
}

namespace {
std::vector<std::string> splitProcesses(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string p; std::getline(in, p, ',');) out.push_back(p);
  return out;
}

std::string describe(const JoinMessage& m, int32_t pid) {
  return (m.processes.empty() ? std::string("nothing") : m.processes) + " on " +
         (m.host.empty() ? std::string("an unnamed host") : m.host) + " (pid " + std::to_string(pid) + ")";
}
}  // namespace

SessionAgreement::SessionAgreement(std::vector<std::string> processes, std::string host,
                                   int64_t scenario_digest, const Nonce& nonce)
    : processes_(std::move(processes)),
      own_processes_(joinProcesses(processes_)),
      host_(std::move(host)),
      digest_(scenario_digest),
      nonce_(nonce) {}

bool SessionAgreement::lists(const JoinMessage& m, const Nonce& nonce) const {
  return std::find(m.heard.begin(), m.heard.end(), nonce) != m.heard.end();
}

bool SessionAgreement::live(const Peer& p, double now) const {
  return now - p.last_heard <= kLiveSeconds && lists(p.said, nonce_);
}

void SessionAgreement::hear(const JoinMessage& m, int32_t pid, double now) {
  if (m.nonce == nonce_) return;  // our own, looped back
  auto it = peers_.find(m.nonce);
  if (it == peers_.end()) {
    if (peers_.size() >= kMaxPeers) {
      // Room for a launcher not heard yet: the longest-silent one that is not live goes.
      auto oldest = peers_.end();
      for (auto p = peers_.begin(); p != peers_.end(); ++p)
        if (!live(p->second, now) &&
            std::find(settled_.begin(), settled_.end(), p->first) == settled_.end() &&
            (oldest == peers_.end() || p->second.last_heard < oldest->second.last_heard))
          oldest = p;
      if (oldest == peers_.end()) return;  // all live: no honest run has so many launchers
      peers_.erase(oldest);
    }
    Peer p;
    p.said = m;
    p.said.heard.clear();
    p.said.agreed = false;
    p.pid = pid;
    it = peers_.emplace(m.nonce, std::move(p)).first;
  }
  // A launcher's messages only ever add nonces and turn agreed on: a replay
  // of an earlier one of them adds nothing, so merging is safe.
  Peer& p = it->second;
  // Bounded: past kMaxPeers nonces, the newest message's alone.
  if (p.said.heard.size() + m.heard.size() > kMaxPeers) p.said.heard.clear();
  for (const Nonce& n : m.heard)
    if (!lists(p.said, n)) p.said.heard.push_back(n);
  p.said.agreed = p.said.agreed || m.agreed;
  p.last_heard = std::max(p.last_heard, now);
}

std::vector<const SessionAgreement::Peer*> SessionAgreement::livePeers(double now) const {
  std::vector<const Peer*> out;
  for (const auto& [nonce, p] : peers_)
    if (live(p, now)) out.push_back(&p);
  return out;
}

JoinMessage SessionAgreement::own(double now) {
  JoinMessage m;
  m.processes = own_processes_;
  m.host = host_;
  m.scenario_digest = digest_;
  m.nonce = nonce_;
  m.agreed = state(now) == State::kAgreed;
  if (m.agreed) {
    // Settled: only the members are listed, so a launcher heard after the
    // agreement (a second one of a member's processes) never finds itself
    // listed, never counts this one as live, and cannot settle on a value
    // of its own with it: it waits and times out, naming this one.
    m.heard = settled_;
    return m;
  }
  // The live ones first: a flood of recorded launchers cannot push them out.
  for (const Peer* p : livePeers(now))
    if (m.heard.size() < kMaxHeard) m.heard.push_back(p->said.nonce);
  std::vector<const Peer*> others;
  for (const auto& [nonce, p] : peers_)
    if (!live(p, now)) others.push_back(&p);
  std::sort(others.begin(), others.end(),
            [](const Peer* a, const Peer* b) { return a->last_heard > b->last_heard; });
  for (const Peer* p : others)
    if (m.heard.size() < kMaxHeard) m.heard.push_back(p->said.nonce);
  return m;
}

std::string SessionAgreement::conflict(double now) const {
  std::map<std::string, std::string> starter;  // process -> who starts it
  for (const std::string& p : processes_) starter[p] = "this launcher";
  for (const Peer* peer : livePeers(now)) {
    if (peer->said.scenario_digest != digest_)
      return "the launcher of " + describe(peer->said, peer->pid) +
             " runs another scenario (its resolved scenario differs from this one's: digest " +
             std::to_string(peer->said.scenario_digest) + ", here " + std::to_string(digest_) +
             "); expected the same scenario file and --set overrides on every host";
    for (const std::string& p : splitProcesses(peer->said.processes)) {
      if (std::find(kProcesses.begin(), kProcesses.end(), p) == kProcesses.end())
        return "the launcher of " + describe(peer->said, peer->pid) + " starts an unknown process '" + p +
               "'";
      auto [it, fresh] = starter.emplace(p, describe(peer->said, peer->pid));
      if (!fresh)
        return "two launchers start the " + p + ": " + it->second + " and " +
               describe(peer->said, peer->pid) +
               "; expected each process on one host only (another run with the same key file, URL and run "
               "id?)";
    }
  }
  return "";
}

SessionAgreement::State SessionAgreement::state(double now) {
  if (agreed_) return State::kAgreed;
  if (!conflict(now).empty()) return State::kConflict;
  const std::vector<const Peer*> members = livePeers(now);
  std::set<std::string> covered(processes_.begin(), processes_.end());
  for (const Peer* p : members)
    for (const std::string& process : splitProcesses(p->said.processes)) covered.insert(process);
  if (covered.size() != kProcesses.size()) return State::kWaiting;
  // Everyone has heard everyone: each derives the same value from the same members.
  for (const Peer* p : members)
    for (const Peer* q : members)
      if (p != q && !lists(p->said, q->said.nonce)) return State::kWaiting;
  // Settled: the value of these members, SHA-256 of their processes and nonces in order.
  std::vector<std::pair<std::string, Nonce>> ordered = {{own_processes_, nonce_}};
  for (const Peer* p : members) {
    ordered.emplace_back(p->said.processes, p->said.nonce);
    settled_.push_back(p->said.nonce);
  }
  std::sort(ordered.begin(), ordered.end());
  std::vector<uint8_t> text;
  static const char kLabel[] = "lagrange run value v1";
  text.insert(text.end(), kLabel, kLabel + sizeof kLabel);
  for (const auto& [processes, nonce] : ordered) {
    text.insert(text.end(), processes.begin(), processes.end());
    text.push_back('\n');
    text.insert(text.end(), nonce.begin(), nonce.end());
  }
  value_ = transport::sha256(text.data(), text.size());
  agreed_ = true;
  return State::kAgreed;
}

std::string SessionAgreement::waitingFor(double now) const {
  std::set<std::string> covered(processes_.begin(), processes_.end());
  for (const Peer* p : livePeers(now))
    for (const std::string& process : splitProcesses(p->said.processes)) covered.insert(process);
  std::vector<std::string> missing;
  for (const std::string& p : kProcesses)
    if (covered.count(p) == 0) missing.push_back(p);
  std::string text =
      missing.empty() ? "every launcher to hear every other" : "the launcher of " + joinProcesses(missing);
  const std::vector<std::string> heard = members(now);
  if (!heard.empty()) {
    text += " (heard ";
    for (size_t i = 0; i < heard.size(); ++i) text += (i ? ", " : "") + heard[i];
    text += ")";
  }
  return text;
}

Nonce SessionAgreement::runValue() const { return value_; }

bool SessionAgreement::everyoneAgreed() const {
  if (!agreed_) return false;
  for (const Nonce& n : settled_) {
    const auto it = peers_.find(n);
    if (it == peers_.end() || !it->second.said.agreed) return false;
  }
  return true;
}

std::vector<std::string> SessionAgreement::members(double now) const {
  std::vector<std::string> out;
  if (agreed_) {
    for (const Nonce& n : settled_)
      if (const auto it = peers_.find(n); it != peers_.end())
        out.push_back(describe(it->second.said, it->second.pid));
    return out;
  }
  for (const Peer* p : livePeers(now)) out.push_back(describe(p->said, p->pid));
  return out;
}

std::size_t SessionAgreement::unanswered(double now) const {
  std::size_t n = 0;
  for (const auto& [nonce, p] : peers_)
    if (!lists(p.said, nonce_) && now - p.last_heard <= kLiveSeconds) ++n;
  return n;
}

}  // namespace lagrange::tools
