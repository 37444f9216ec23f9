// What binds a message to its run beyond the key (docs/reliability.md "Threat
// model"): the run key derived from a shared key and a fresh value
// (transport::deriveRunKey), the launchers' agreement on that value
// (tools/run/session_agreement.hpp) with recorded launchers of another run in
// the air, the header checks that keep a replaced process from being heard
// again (transport/header_admission.hpp), and the logger's record filter
// (logger/record_filter.hpp).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "lagrange/plant_position_t.hpp"
#include "lagrange/status_t.hpp"
#include "logger/record_filter.hpp"
#include "tools/run/session_agreement.hpp"
#include "transport/channels.hpp"
#include "transport/checksum.hpp"
#include "transport/header_admission.hpp"
#include "transport/message_auth.hpp"

namespace lagrange::testing {
namespace {

using tools::JoinMessage;
using tools::Nonce;
using tools::SessionAgreement;
using transport::HeaderAdmission;
using transport::RejectReason;

Nonce nonceOf(uint8_t fill) {
  Nonce n;
  n.fill(fill);
  return n;
}

TEST(RunKey, DependsOnTheSharedKeyAndTheRunsValueAndIsNeitherOfThem) {
  transport::MessageKey shared;
  shared.fill(7);
  const transport::MessageKey a = transport::deriveRunKey(shared, nonceOf(1));
  EXPECT_EQ(a, transport::deriveRunKey(shared, nonceOf(1)));  // every launcher derives the same
  EXPECT_NE(a, transport::deriveRunKey(shared, nonceOf(2)));  // another run: another key
  transport::MessageKey other = shared;
  other[0] ^= 1;
  EXPECT_NE(a, transport::deriveRunKey(other, nonceOf(1)));
  EXPECT_NE(a, shared);
  // A datagram signed under one run's key fails under the next run's.
  std::vector<uint8_t> datagram = {1, 2, 3};
  transport::MessageAuthenticator(a).sign(datagram);
  EXPECT_TRUE(transport::MessageAuthenticator(a).verify(datagram.data(), datagram.size()));
  EXPECT_FALSE(transport::MessageAuthenticator(transport::deriveRunKey(shared, nonceOf(2)))
                   .verify(datagram.data(), datagram.size()));
  EXPECT_NE(transport::randomNonce(), transport::randomNonce());
}

// Two launchers, the plant's side and the logger's side, passing messages
// back and forth; `air` is what else is heard on the URL.
struct Launchers {
  SessionAgreement a{{"actuator", "plant"}, "host-a", 99, nonceOf(0xa)};
  SessionAgreement b{{"logger", "controller"}, "host-b", 99, nonceOf(0xb)};
  void exchange(double now, const std::vector<JoinMessage>& air = {}) {
    const JoinMessage from_a = a.own(now), from_b = b.own(now);
    for (const JoinMessage& m : air) {
      a.hear(m, 7, now);
      b.hear(m, 7, now);
    }
    b.hear(from_a, 100, now);
    a.hear(from_b, 200, now);
  }
};

TEST(SessionAgreement, TwoLaunchersAgreeOnOneValueAfterHearingEachOther) {
  Launchers l;
  EXPECT_EQ(l.a.state(0.0), SessionAgreement::State::kWaiting);
  EXPECT_NE(l.a.waitingFor(0.0).find("logger,controller"), std::string::npos) << l.a.waitingFor(0.0);
  l.exchange(0.0);  // each hears the other, neither is listed yet
  EXPECT_EQ(l.a.state(0.0), SessionAgreement::State::kWaiting);
  l.exchange(0.1);  // each now lists the other
  ASSERT_EQ(l.a.state(0.1), SessionAgreement::State::kAgreed);
  ASSERT_EQ(l.b.state(0.1), SessionAgreement::State::kAgreed);
  EXPECT_EQ(l.a.runValue(), l.b.runValue());
  EXPECT_FALSE(l.a.everyoneAgreed());  // b has not said so yet
  l.exchange(0.2);
  EXPECT_TRUE(l.a.everyoneAgreed());
  EXPECT_EQ(l.a.members(0.2), std::vector<std::string>{"logger,controller on host-b (pid 200)"});
  // Another pair with fresh nonces: another value.
  SessionAgreement c{{"actuator", "plant"}, "host-a", 99, nonceOf(0xc)};
  c.hear(l.b.own(0.2), 200, 0.2);
  EXPECT_NE(c.state(0.2), SessionAgreement::State::kAgreed);  // b never listed c's nonce
}

// The attack of issue #44: another run's launchers, recorded and re-sent,
// are never counted: they cannot list the fresh nonces of this run's.
TEST(SessionAgreement, RecordedLaunchersOfAnotherRunAreNeverCounted) {
  Launchers old_run;
  old_run.a = SessionAgreement{{"actuator", "plant"}, "host-a", 99, nonceOf(0x1a)};
  old_run.b = SessionAgreement{{"logger", "controller"}, "host-b", 99, nonceOf(0x1b)};
  old_run.exchange(0.0);
  old_run.exchange(0.1);
  const std::vector<JoinMessage> recorded = {old_run.a.own(0.2), old_run.b.own(0.2)};
  ASSERT_TRUE(recorded[0].agreed);
  // The plant's launcher alone, hearing only the recording: waits, forever.
  SessionAgreement alone{{"actuator", "plant"}, "host-a", 99, nonceOf(0xa)};
  for (double t = 0; t < 2; t += 0.1) alone.hear(recorded[1], 200, t);
  EXPECT_EQ(alone.state(2.0), SessionAgreement::State::kWaiting);
  EXPECT_EQ(alone.unanswered(2.0), 1u);
  // Both of this run's launchers, with the recording re-sent all along: they
  // agree with each other, and the recorded ones are in no one's value.
  Launchers now;
  for (double t = 0; t < 0.5; t += 0.1) now.exchange(t, recorded);
  ASSERT_EQ(now.a.state(0.5), SessionAgreement::State::kAgreed);
  EXPECT_EQ(now.a.runValue(), now.b.runValue());
  EXPECT_NE(now.a.runValue(), old_run.a.runValue());
  EXPECT_EQ(now.a.members(0.5).size(), 1u);
}

TEST(SessionAgreement, TwoLiveLaunchersOfOneProcessOrAnotherScenarioConflict) {
  Launchers l;
  SessionAgreement intruder{{"controller"}, "host-c", 99, nonceOf(0xc)};
  for (double t = 0; t < 0.3; t += 0.1) {  // the intruder heard first: no agreement settles without it
    intruder.hear(l.a.own(t), 100, t);
    l.a.hear(intruder.own(t), 300, t);
    l.exchange(t);
  }
  ASSERT_EQ(l.a.state(0.3), SessionAgreement::State::kConflict);
  const std::string why = l.a.conflict(0.3);
  EXPECT_NE(why.find("two launchers start the controller"), std::string::npos) << why;
  EXPECT_NE(why.find("host-c (pid 300)"), std::string::npos) << why;
  // Once it falls silent (stopped), it no longer counts.
  l.exchange(0.4);
  l.exchange(0.5);
  l.exchange(1.5);
  EXPECT_EQ(l.a.state(1.5), SessionAgreement::State::kAgreed);

  SessionAgreement other{{"logger", "controller"}, "host-b", 1234, nonceOf(0xd)};
  SessionAgreement a{{"actuator", "plant"}, "host-a", 99, nonceOf(0xa)};
  for (double t = 0; t < 0.3; t += 0.1) {
    other.hear(a.own(t), 100, t);
    a.hear(other.own(t), 200, t);
  }
  EXPECT_NE(a.conflict(0.3).find("runs another scenario"), std::string::npos) << a.conflict(0.3);
}

std::vector<JoinMessage> recordedLaunchers(int count) {
  std::vector<JoinMessage> flood;
  for (int i = 0; i < count; ++i) {
    JoinMessage m;
    m.processes = "controller,logger";
    m.scenario_digest = 99;
    m.nonce = nonceOf(0);
    m.nonce[0] = static_cast<uint8_t>(i);
    m.nonce[1] = static_cast<uint8_t>(i >> 8);
    m.nonce[2] = 0x77;
    flood.push_back(m);
  }
  return flood;
}

// Found in review: a second launcher of the logger's processes heard only
// after the plant's launcher had agreed with the first would be listed by
// it, count it as live, and settle on a value of its own -- two runs'
// processes under two keys. Once agreed, a launcher lists its members only.
TEST(SessionAgreement, ALauncherHeardAfterTheAgreementNeverSettlesWithAMember) {
  Launchers l;
  l.exchange(0.0);
  l.exchange(0.1);
  ASSERT_EQ(l.a.state(0.1), SessionAgreement::State::kAgreed);
  SessionAgreement late{{"logger", "controller"}, "host-c", 99, nonceOf(0xc)};
  for (double t = 0.2; t < 3.0; t += 0.1) {
    late.hear(l.a.own(t), 100, t);
    l.a.hear(late.own(t), 300, t);
  }
  EXPECT_EQ(late.state(3.0), SessionAgreement::State::kWaiting);
  EXPECT_EQ(late.unanswered(3.0), 1u);
  EXPECT_EQ(l.a.own(3.0).heard, std::vector<Nonce>{nonceOf(0xb)});
}

// Up to kMaxPeers recorded launchers, the live ones still agree; past it the
// memory and the message stay bounded (agreement is then not promised).
TEST(SessionAgreement, AFloodOfRecordedLaunchersIsBoundedAndUpTo256LeaveTheLiveOnesAgreeing) {
  Launchers l;
  l.exchange(0.0, recordedLaunchers(200));
  EXPECT_EQ(l.a.own(0.05).heard.size(), 201u);  // before agreeing: every launcher heard
  for (double t = 0.1; t < 0.5; t += 0.1) l.exchange(t, recordedLaunchers(200));
  EXPECT_EQ(l.a.state(0.5), SessionAgreement::State::kAgreed);
  EXPECT_EQ(l.a.runValue(), l.b.runValue());
  Launchers flooded;
  flooded.exchange(0.0, recordedLaunchers(2000));
  EXPECT_EQ(flooded.a.own(0.05).heard.size(), SessionAgreement::kMaxHeard);
}

lagrange::header_t header(int32_t pid, int64_t seq, int64_t utime) {
  lagrange::header_t h{};
  h.run_id = 42;
  h.publisher = "controller";
  h.publisher_pid = pid;
  h.seq = seq;
  h.publish_utime = utime;
  return h;
}

// A restarted process takes over its channel; the one it replaced, or any
// earlier process of the run re-sent from a recording, opens no window.
TEST(HeaderAdmission, ANewPidTakesOverOnlyWhenLaterAndAReplacedOneIsNeverHeardAgain) {
  for (const auto order : {HeaderAdmission::Order::kNewestOnly, HeaderAdmission::Order::kAcceptReordered}) {
    HeaderAdmission admit(42);
    const std::string ch = transport::kControlCommand;
    EXPECT_FALSE(admit.admit(ch, header(10, 1, 1000), order));
    EXPECT_FALSE(admit.admit(ch, header(10, 2, 1001), order));
    // An earlier process's message, recorded and re-sent: older than the current one's.
    const auto replay = admit.admit(ch, header(9, 57, 900), order);
    ASSERT_TRUE(replay);
    EXPECT_EQ(replay->reason, RejectReason::kOldOrRepeated);
    EXPECT_NE(replay->detail.find("not a restart"), std::string::npos) << replay->detail;
    // The restart: later, numbers from 1 again.
    EXPECT_FALSE(admit.admit(ch, header(11, 1, 2000), order));
    EXPECT_FALSE(admit.admit(ch, header(11, 2, 2001), order));
    // The replaced process, even with a later stamp (a message it sent late): refused.
    const auto replaced = admit.admit(ch, header(10, 3, 2500), order);
    ASSERT_TRUE(replaced);
    EXPECT_NE(replaced->detail.find("which pid 11 replaced"), std::string::npos) << replaced->detail;
    EXPECT_TRUE(admit.admit(ch, header(11, 2, 2600), order));  // a repeat of the current one
    EXPECT_FALSE(admit.admit(ch, header(11, 3, 2002), order));
    // Another channel, another run: unaffected / refused as before.
    EXPECT_FALSE(admit.admit(transport::kStatus, header(10, 1, 1000), order));
    lagrange::header_t foreign = header(11, 4, 3000);
    foreign.run_id = 43;
    EXPECT_EQ(admit.admit(ch, foreign, order)->reason, RejectReason::kOtherRun);
  }
}

template <class Msg>
std::vector<uint8_t> bytesOf(Msg m) {
  transport::seal(m);
  std::vector<uint8_t> out(static_cast<size_t>(m.getEncodedSize()));
  m.encode(out.data(), 0, static_cast<int>(out.size()));
  return out;
}

// The logger records what the run's processes would accept by the header,
// and counts the rest (summary.json log.not_recorded).
TEST(RecordFilter, RecordsEachMessageOfThisRunOnceAndCountsTheRest) {
  logger::RecordFilter filter(42);
  lagrange::plant_position_t p{};
  p.header = header(5, 1, 100);
  p.header.publisher = "plant";
  const auto first = bytesOf(p);
  EXPECT_TRUE(filter.admit(transport::kPlantPosition, first.data(), first.size()));
  EXPECT_FALSE(filter.admit(transport::kPlantPosition, first.data(), first.size()));  // re-sent
  p.header.run_id = 43;
  p.header.seq = 2;
  const auto other_run = bytesOf(p);
  EXPECT_FALSE(filter.admit(transport::kPlantPosition, other_run.data(), other_run.size()));
  p.header.run_id = 42;
  p.header.publisher = "controller";
  const auto wrong = bytesOf(p);
  EXPECT_FALSE(filter.admit(transport::kPlantPosition, wrong.data(), wrong.size()));
  const std::vector<uint8_t> junk(40, 0x5a);
  EXPECT_FALSE(filter.admit(transport::kPlantPosition, junk.data(), junk.size()));
  EXPECT_TRUE(filter.admit("SOMEONE_ELSES", junk.data(), junk.size()));  // not the project's: as before
  lagrange::status_t st{};
  st.header = header(5, 1, 100);
  st.header.publisher = "plant";
  const auto status = bytesOf(st);
  EXPECT_TRUE(filter.admit(transport::kStatus, status.data(), status.size()));
  const auto& counts = filter.notRecorded().at(transport::kPlantPosition);
  EXPECT_EQ(counts.at("old_or_repeated"), 1);
  EXPECT_EQ(counts.at("other_run"), 1);
  EXPECT_EQ(counts.at("wrong_publisher"), 1);
  EXPECT_EQ(counts.at("undecodable"), 1);
}

// A tick outside the run's [0, last tick] is no message of the run: not
// recorded, counted (a plant publishing past the end must not pad the log).
TEST(RecordFilter, TicksOutsideTheRunAreNotRecordedAndCounted) {
  logger::RecordFilter filter(42, 200);
  lagrange::plant_truth_t t{};
  t.header = header(5, 1, 100);
  t.header.publisher = "plant";
  t.header.tick = 200;
  const auto last = bytesOf(t);
  EXPECT_TRUE(filter.admit(transport::kPlantTruth, last.data(), last.size()));
  for (const int64_t tick : {int64_t{201}, int64_t{1000000000000000}, int64_t{-1}}) {
    t.header.seq++;
    t.header.tick = tick;
    const auto outside = bytesOf(t);
    EXPECT_FALSE(filter.admit(transport::kPlantTruth, outside.data(), outside.size())) << tick;
  }
  lagrange::status_t st{};
  st.header = header(5, 1, 100);  // STATUS is no per-tick message: its tick is a process's last
  st.header.publisher = "plant";
  st.header.tick = 5000;
  const auto status = bytesOf(st);
  EXPECT_TRUE(filter.admit(transport::kStatus, status.data(), status.size()));
  EXPECT_EQ(filter.notRecorded().at(transport::kPlantTruth).at("outside_run"), 3);
}

}  // namespace
}  // namespace lagrange::testing
