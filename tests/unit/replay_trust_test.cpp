// lagrange replay of golden logs crafted into lies and damage (#44), in
// process: a chain state with more or fewer rows than the chain is refused
// naming the tick, the count found and the count expected -- never read past
// (it crashed), never "reproduced" unread --; a log that lacks an output, or
// holds a corrupt copy of one, is named as such -- tick, byte offset -- and
// never as a component that DIVERGED.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "support/configs.hpp"
#include "support/log_events.hpp"
#include "support/temp_dir.hpp"
#include "tools/replay/replay.hpp"
#include "tools/replay/shell_words.hpp"

namespace lagrange::testing {
namespace {

using tools::ReplayError;
using tools::ReplayResult;

class ReplayTrust : public TempDirTest {
 protected:
  std::string write(const std::vector<LoggedEvent>& events, const std::string& name) {
    const std::string path = dir_ + "/" + name + ".lcm";
    writeEvents(path, events);
    return path;
  }

  // The golden log with ACTUATOR_STATE tick `tick` holding `rows` chain rows
  // (its order field saying so), sealed: an intact message that lies.
  std::string withChainRows(const std::string& golden, int64_t tick, int rows) {
    std::vector<LoggedEvent> events = readEvents(kGoldenDir + golden + ".lcm");
    LoggedEvent& e = events[indexOf<lagrange::actuator_state_t>(events, "ACTUATOR_STATE", tick)];
    auto state = decodeAs<lagrange::actuator_state_t>(e);
    state.xi.resize(static_cast<size_t>(rows),
                    std::vector<double>(static_cast<size_t>(state.num_joints), 0.25));
    state.order = rows;
    encodeSealed(e, state);
    return write(events, golden + "-" + std::to_string(rows) + "-rows");
  }
};

// The refusal every replay of a log that lies must end in: bad input (exit 2), naming `expected`.
template <class Replay>
void expectRefused(Replay replay, const std::string& log, const std::vector<std::string>& expected) {
  try {
    const ReplayResult r = replay(log, std::vector<std::string>{});
    ADD_FAILURE() << "replayed " << r.commands << " outputs"
                  << (r.divergence ? ", DIVERGED at " + *r.divergence : std::string(", all reproduced"));
  } catch (const ReplayError& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kBadInput) << e.what();
    for (const std::string& part : expected)
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find("DIVERGED"), std::string::npos) << e.what();
  }
}

const auto kActuator = [](const std::string& log, const std::vector<std::string>& o) {
  return tools::replayActuator(log, o);
};
const auto kController = [](const std::string& log, const std::vector<std::string>& o) {
  return tools::replayController(log, o);
};
const auto kPlant = [](const std::string& log, const std::vector<std::string>& o) {
  return tools::replayPlant(log, o);
};

// #44 finding 3: an order-0 log with one chain row crashed the actuator's
// replay with SIGSEGV (row 0 of a chain with none).
TEST_F(ReplayTrust, AnOrderZeroLogWithAChainRowIsRefused) {
  const std::string log = withChainRows("rigid_2dof_lockstep", 100, 1);
  expectRefused(kActuator, log,
                {"ACTUATOR_STATE tick 100 (the event at byte ",
                 "holds 1 chain row (order), expected 0 (actuator.order)"});
  // The plant applies that state's torque over tick 101: it is refused there too.
  expectRefused(kPlant, log, {"ACTUATOR_STATE tick 100", "expected 0 (actuator.order)"});
}

// A chain_m2 log with 3 rows: the third was read from beyond the chain's
// state; the controller reads the rows as its input xi.
TEST_F(ReplayTrust, AChainM2LogWithThreeChainRowsIsRefused) {
  const std::string log = withChainRows("chain_m2_lockstep", 100, 3);
  expectRefused(kActuator, log,
                {"ACTUATOR_STATE tick 100", "holds 3 chain rows (order), expected 2 (actuator.order)"});
  expectRefused(kController, log, {"ACTUATOR_STATE tick 100", "holds 3 chain rows (order), expected 2"});
}

// With 0 or 1 rows, the rows it lacked were never compared and the replay
// claimed every output "bit for bit".
TEST_F(ReplayTrust, AChainM2LogWithTooFewChainRowsIsRefusedNotReproduced) {
  for (const int rows : {0, 1}) {
    const std::string log = withChainRows("chain_m2_lockstep", 100, rows);
    expectRefused(kActuator, log,
                  {"ACTUATOR_STATE tick 100", "holds " + std::to_string(rows) + " chain row",
                   "expected 2 (actuator.order)"});
  }
}

// #44 finding 6: a log without one CONTROL_COMMAND made replay say "controller
// DIVERGED at tick 532" -- the controller's filter skipped a step the log lacked.
TEST_F(ReplayTrust, AMissingCommandIsNamedAsAGapNotADivergence) {
  std::vector<LoggedEvent> events = readEvents(kGoldenRigidLockstep);
  events.erase(events.begin() +
               static_cast<long>(indexOf<lagrange::control_command_t>(events, "CONTROL_COMMAND", 531)));
  const std::string log = write(events, "without-command-531");
  expectRefused(kController, log,
                {"the log lacks CONTROL_COMMAND tick 531 (the next it holds is tick 532",
                 "the 531 outputs before it were replayed bit for bit"});
  // The actuator answered it: its replay names the same gap as its missing input.
  expectRefused(kActuator, log,
                {"the log lacks CONTROL_COMMAND tick 531, an input of ACTUATOR_STATE tick 531"});
}

// The same in a realtime log, where the controller skips samples it had no
// fresh input for: a gap is a jump in the sequence numbers it gives every
// command it publishes.
TEST_F(ReplayTrust, AMissingCommandOfARealtimeLogIsNamedAsAGap) {
  std::vector<LoggedEvent> events = readEvents(kGoldenDir + "chain_m1_realtime.lcm");
  const size_t at = indexOf<lagrange::control_command_t>(events, "CONTROL_COMMAND", 400);
  const int64_t seq = decodeAs<lagrange::control_command_t>(events[at]).header.seq;
  events.erase(events.begin() + static_cast<long>(at));
  expectRefused(
      kController, write(events, "realtime-without-command-400"),
      {"the log lacks 1 CONTROL_COMMAND message the controller published between tick 399 and tick 401",
       "(sequence number " + std::to_string(seq) + ";"});
}

// An ACTUATOR_STATE the log lacks: the chain skipped a step, and the next state "DIVERGED".
TEST_F(ReplayTrust, AMissingActuatorStateIsNamedAsAGap) {
  std::vector<LoggedEvent> events = readEvents(kGoldenDir + "chain_m2_lockstep.lcm");
  events.erase(events.begin() +
               static_cast<long>(indexOf<lagrange::actuator_state_t>(events, "ACTUATOR_STATE", 300)));
  expectRefused(kActuator, write(events, "without-state-300"),
                {"the log lacks ACTUATOR_STATE tick 300 (the next it holds is tick 301"});
}

// One bit flipped inside a command: its checksum fails, it is skipped, and
// the gap it leaves is named with the corrupt copy's byte offset.
TEST_F(ReplayTrust, ACorruptCommandIsNamedWithItsOffset) {
  std::vector<LoggedEvent> events = readEvents(kGoldenRigidLockstep);
  const size_t at = indexOf<lagrange::control_command_t>(events, "CONTROL_COMMAND", 531);
  // In the last filter_state value (the message ends with it and chain_order, an int32 0 here).
  events[at].data[events[at].data.size() - 7] ^= 0x10;
  const std::string log = write(events, "corrupt-command-531");
  expectRefused(kController, log,
                {"the log lacks CONTROL_COMMAND tick 531",
                 "the copy of CONTROL_COMMAND tick 531 it holds is corrupt: the event at byte " +
                     std::to_string(offsetOf(events, at)) + " fails its checksum"});
}

// #44 finding 6, random damage: bits flipped anywhere after the scenario and
// the arm's description (seeded). Every replay either reproduces what is left
// or refuses naming the damage; none says DIVERGED.
TEST_F(ReplayTrust, RandomBitFlipsAreNamedNeverTakenForADivergence) {
  const std::vector<LoggedEvent> golden = readEvents(kGoldenRigidLockstep);
  const long long first = offsetOf(golden, 2), size = offsetOf(golden, golden.size());
  int refusals_naming_damage = 0;
  for (unsigned seed = 1; seed <= 4; ++seed) {
    std::ifstream in(kGoldenRigidLockstep, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::mt19937_64 random(seed);
    std::uniform_int_distribution<long long> where(first, size - 1);
    for (int flip = 0; flip < 8; ++flip) {
      const auto at = static_cast<size_t>(where(random));  // then the bit: one order on every compiler
      bytes[at] = static_cast<char>(bytes[at] ^ (1 << (random() % 8)));
    }
    const std::string log = dir_ + "/flipped-" + std::to_string(seed) + ".lcm";
    std::ofstream(log, std::ios::binary) << bytes;
    for (const auto& [name, replay] : std::vector<std::pair<
             std::string, std::function<ReplayResult(const std::string&, const std::vector<std::string>&)>>>{
             {"controller", kController}, {"actuator", kActuator}, {"plant", kPlant}}) {
      try {
        const ReplayResult r = replay(log, {});
        // What is left reproduces: the flips hit nothing this component reads, or a
        // copy it does not need (a timestamp, another channel's message: warned of).
        EXPECT_FALSE(r.divergence) << "seed " << seed << ": " << name << " DIVERGED at " << *r.divergence;
        std::printf("seed %u, %s: %lld outputs reproduced, %zu warnings\n", seed, name.c_str(), r.commands,
                    r.warnings.size());
      } catch (const ReplayError& e) {
        const std::string what = e.what();
        EXPECT_EQ(e.kind(), ErrorKind::kBadInput) << what;
        // A gap, a corrupt copy or a malformed event -- and where: the byte offset of the damage.
        const bool named =
            (what.find("corrupt") != std::string::npos || what.find("malformed") != std::string::npos ||
             what.find("the log lacks") != std::string::npos) &&
            what.find(" byte ") != std::string::npos;
        EXPECT_TRUE(named) << "seed " << seed << ": " << name << ": " << what;
        refusals_naming_damage += named;
        std::printf("seed %u, %s: refused: %s\n", seed, name.c_str(), what.c_str());
      }
    }
  }
  EXPECT_GT(refusals_naming_damage, 0) << "no flip hit a message replay needed: the test tests nothing";
}

// A command read from a log is shown as a shell reads it back, and no byte of
// it reaches the terminal as a control character.
// #44 finding 4: one honest-looking ACTUATOR_STATE far larger than any of
// the log's scenario can be (here 200 000 chain rows, 5 MB; the battery's was
// 241 MB, gigabytes once decoded) is skipped unread by replay -- the log's
// scenario bounds every event (logs/event_bounds.hpp) -- and named; the
// replay itself goes on with the copy of that tick it holds.
TEST_F(ReplayTrust, AnEventLargerThanTheLogsScenarioAllowsIsSkippedUnreadAndNamed) {
  std::vector<LoggedEvent> events = readEvents(kGoldenDir + std::string("rigid_2dof_lockstep.lcm"));
  LoggedEvent big = events[indexOf<lagrange::actuator_state_t>(events, "ACTUATOR_STATE", 5)];
  auto state = decodeAs<lagrange::actuator_state_t>(big);
  state.order = 200000;
  state.xi.assign(200000, std::vector<double>(static_cast<size_t>(state.num_joints), 0.25));
  encodeSealed(big, state);
  events.push_back(big);
  const ReplayResult r = tools::replayActuator(write(events, "oversized"), {});
  EXPECT_FALSE(r.divergence) << *r.divergence;
  std::string warnings;
  for (const std::string& w : r.warnings) warnings += w + "\n";
  EXPECT_NE(warnings.find("1 event was larger than its channel's messages can be and skipped unread"),
            std::string::npos)
      << warnings;
}

TEST(ShellWords, QuoteEveryWordAndEscapeControlBytes) {
  EXPECT_EQ(tools::shellWord("python3"), "'python3'");
  EXPECT_EQ(tools::shellWord("a b"), "'a b'");
  EXPECT_EQ(tools::shellWord("it's"), "'it'\\''s'");
  EXPECT_EQ(tools::shellWord(""), "''");
  EXPECT_EQ(tools::shellWord("\x1b[2J"), "$'\\x1b[2J'");
  EXPECT_EQ(tools::shellWord("caf\xc3\xa9 'x'\\"), "$'caf\\xc3\\xa9 \\'x\\'\\\\'");
  EXPECT_EQ(tools::shellWords({"sh", "-c", "touch x"}), "'sh' '-c' 'touch x'");
  EXPECT_EQ(tools::shellWords({std::string(30, 'a')}, 10), "'aaaaaaaaa... (22 more characters)");
}

}  // namespace
}  // namespace lagrange::testing
