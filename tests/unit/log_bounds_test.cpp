// Every event of a log is bounded by what its channel's messages can be in
// the log's own scenario (logs/event_bounds.hpp): the bounds are lcm-gen's
// encoded sizes (transport/message_size.hpp), an event over its bound is skipped unread -- no reader
// ever gets it to decode -- and named, a SCENARIO larger than any scenario
// refuses the log, and the golden logs read whole as before.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/plant_truth_t.hpp"
#include "lagrange/scenario_t.hpp"
#include "logs/event_bounds.hpp"
#include "logs/log_reader.hpp"
#include "support/configs.hpp"
#include "transport/header_admission.hpp"
#include "transport/message_size.hpp"

namespace lagrange::logs {
namespace {

namespace fs = std::filesystem;

// A message with every count at the shape's value and the longest publisher.
using transport::kMaxPublisherBytes;
namespace encoded_size = transport::encoded_size;

template <class Msg>
Msg withLongestPublisher(Msg m) {
  m.header.publisher = std::string(static_cast<std::size_t>(kMaxPublisherBytes), 'p');
  return m;
}

std::vector<double> zeros(int n) { return std::vector<double>(static_cast<std::size_t>(n), 0.0); }
std::vector<std::vector<double>> rows(int count, int n) {
  return std::vector<std::vector<double>>(static_cast<std::size_t>(count), zeros(n));
}

TEST(EventBounds, TheFormulasAreTheEncodedSizesLcmGenComputes) {
  for (const MessageShape shape : {shapeOf(1, 0, 1), shapeOf(2, 2, 3), shapeOf(7, 4, 5)}) {
    SCOPED_TRACE(shape.describe());
    const int n = shape.joints;
    lagrange::plant_position_t position{};
    position.num_joints = n;
    position.q = zeros(n);
    EXPECT_EQ(encoded_size::plantPosition(shape), withLongestPublisher(position).getEncodedSize());
    lagrange::plant_truth_t truth{};
    truth.num_joints = n;
    truth.q = truth.qdot = truth.tau_applied = zeros(n);
    EXPECT_EQ(encoded_size::plantTruth(shape), withLongestPublisher(truth).getEncodedSize());
    lagrange::plant_motor_t motor{};
    motor.num_joints = motor.num_rates = n;
    motor.q = motor.qdot = zeros(n);
    EXPECT_EQ(encoded_size::plantMotor(shape), withLongestPublisher(motor).getEncodedSize());
    lagrange::control_command_t command{};
    command.num_joints = n;
    command.u = command.q_desired = command.q_error = command.theta = command.filter_state = zeros(n);
    command.chain_order = 4;  // the most stages any controller reports
    command.xi_error = rows(4, n);
    EXPECT_EQ(encoded_size::controlCommand(shape), withLongestPublisher(command).getEncodedSize());
    lagrange::actuator_state_t state{};
    state.num_joints = n;
    state.order = shape.chain_order;
    state.u_commanded = zeros(n);
    state.torque_steps = shape.torque_steps;
    state.tau_applied = rows(shape.torque_steps, n);
    state.saturated.assign(static_cast<std::size_t>(n), false);
    state.xi = rows(shape.chain_order, n);
    EXPECT_EQ(encoded_size::actuatorState(shape), withLongestPublisher(state).getEncodedSize());
  }
}

void putBigEndian(std::string& out, uint64_t value, int bytes) {
  for (int i = bytes - 1; i >= 0; --i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
}

// One event in the LCM log format.
std::string logEvent(int64_t number, const std::string& channel, const std::string& data) {
  std::string out;
  putBigEndian(out, 0xEDA1DA01u, 4);
  putBigEndian(out, static_cast<uint64_t>(number), 8);
  putBigEndian(out, 1700000000000000ULL + static_cast<uint64_t>(number), 8);
  putBigEndian(out, channel.size(), 4);
  putBigEndian(out, data.size(), 4);
  return out + channel + data;
}

template <class Msg>
std::string encoded(const Msg& m) {
  std::string bytes(static_cast<std::size_t>(m.getEncodedSize()), '\0');
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// The default scenario's SCENARIO event: 2 joints, actuator order 0, 1 torque step a tick.
std::string scenarioEvent() {
  lagrange::scenario_t m{};
  m.name = "rigid_2dof";
  m.yaml = config::toYaml(config::loadScenario(testing::kRigid));
  return logEvent(0, "SCENARIO", encoded(m));
}

// An ACTUATOR_STATE whose lengths are all consistent: `steps` rows of `joints` joints.
std::string actuatorStateEvent(int64_t number, int64_t tick, int joints, int steps) {
  lagrange::actuator_state_t m{};
  m.header.tick = tick;
  m.header.publisher = "actuator";
  m.num_joints = joints;
  m.u_commanded = zeros(joints);
  m.torque_steps = steps;
  m.tau_applied = rows(steps, joints);
  m.saturated.assign(static_cast<std::size_t>(joints), false);
  return logEvent(number, "ACTUATOR_STATE", encoded(m));
}

class LogBoundsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("lagrange-log-bounds-" + std::to_string(getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& bytes) {
    const std::string path = (dir_ / "crafted.lcm").string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  static std::string joined(const std::vector<std::string>& lines) {
    std::string all;
    for (const std::string& l : lines) all += l + "\n";
    return all;
  }
  fs::path dir_;
};

// The attack, smaller: an ACTUATOR_STATE of 200 000 one-joint rows
// (1.6 MB; 30 million rows took replay to 3.5 GB) in a log whose scenario
// has 2 joints and 1 torque step a tick. No reader gets it to decode.
TEST_F(LogBoundsTest, AnEventLargerThanItsScenarioAllowsIsSkippedUnreadAndNamed) {
  const std::string head = scenarioEvent() + actuatorStateEvent(1, 0, 2, 1);
  const std::string crafted = actuatorStateEvent(2, 7, 1, 200000);
  const std::string path = write(head + crafted + actuatorStateEvent(3, 1, 2, 1));
  std::vector<std::string> handed;
  std::vector<int32_t> sizes;
  const LogScan scan = readLog(path, [&](const lcm::LogEvent& ev) {
    handed.push_back(ev.channel);
    sizes.push_back(ev.datalen);
  });
  EXPECT_EQ(handed, (std::vector<std::string>{"SCENARIO", "ACTUATOR_STATE", "ACTUATOR_STATE"}));
  for (const int32_t size : sizes) EXPECT_LT(size, 100000);
  EXPECT_EQ(scan.events, 3);
  EXPECT_EQ(scan.oversized_events, 1);
  EXPECT_EQ(scan.oversized_bytes, static_cast<long long>(crafted.size()));
  const long long bound = encoded_size::actuatorState(shapeOf(2, 0, 1)) + 32;
  const std::string warnings = joined(scan.problems());
  EXPECT_NE(warnings.find("1 event was larger than its channel's messages can be and skipped unread, never "
                          "decoded (ACTUATOR_STATE at byte " +
                          std::to_string(head.size()) + " (tick 7): " + std::to_string(crafted.size() - 42) +
                          " bytes, at most " + std::to_string(bound) + " expected)"),
            std::string::npos)
      << warnings;
  EXPECT_NE(
      warnings.find("the log's scenario (2 joints, actuator order 0, 1 torque step a tick, ticks 0 to "),
      std::string::npos)
      << warnings;
}

// A tick the log's scenario never had (10^15 in a short log; a flood of
// ticks past its end) is dropped and counted: no reader keeps it.
TEST_F(LogBoundsTest, AnEventForATickOutsideTheScenarioIsDroppedAndCounted) {
  const std::string head = scenarioEvent() + actuatorStateEvent(1, 0, 2, 1);
  const std::string far = actuatorStateEvent(2, 1000000000000000LL, 2, 1);
  std::string past;
  for (int k = 0; k < 50; ++k) past += actuatorStateEvent(3 + k, 10001 + k, 2, 1);
  const std::string path = write(head + far + past + actuatorStateEvent(60, 10000, 2, 1));
  std::vector<long long> ticks;
  const LogScan scan = readLog(path, [&](const lcm::LogEvent& ev) {
    lagrange::header_t h;
    if (ev.channel == "ACTUATOR_STATE" && transport::peekHeader(ev.channel, ev.data, ev.datalen, h))
      ticks.push_back(h.tick);
  });
  EXPECT_EQ(ticks, (std::vector<long long>{0, 10000}));  // the scenario's last tick is 10000
  EXPECT_EQ(scan.outside_run, 51);
  ASSERT_FALSE(scan.first_outside.empty());
  EXPECT_EQ(scan.first_outside.front().tick, 1000000000000000LL);
  const std::string warnings = joined(scan.problems());
  EXPECT_NE(warnings.find("51 events for a tick outside the run were dropped (the first at byte " +
                          std::to_string(head.size()) + ", tick 1000000000000000)"),
            std::string::npos)
      << warnings;
}

// A log without a SCENARIO (a stock lcm-logger started late) is bounded by
// the project's limits: 16 joints, order 4, 100 000 torque steps a tick.
TEST_F(LogBoundsTest, WithoutAScenarioEventsAreBoundedByTheProjectsLimits) {
  const long long largest = encoded_size::actuatorState(projectLimits()) + 32;
  const std::string fits =
      logEvent(0, "ACTUATOR_STATE", std::string(static_cast<std::size_t>(largest), '\0'));
  const std::string over =
      logEvent(1, "ACTUATOR_STATE", std::string(static_cast<std::size_t>(largest) + 1, '\0'));
  long long handed = 0;
  const LogScan scan = readLog(write(fits + over), [&](const lcm::LogEvent&) { ++handed; });
  EXPECT_EQ(handed, 1);
  EXPECT_EQ(scan.oversized_events, 1);
  EXPECT_NE(joined(scan.problems())
                .find("no SCENARIO in the log: the project's limits (16 joints, actuator order 4, 100000 "
                      "torque steps a tick)"),
            std::string::npos)
      << joined(scan.problems());
}

// A SCENARIO larger than any scenario can be refuses the log, naming it;
// its bytes are never read.
TEST_F(LogBoundsTest, ASCENARIOLargerThanAnyScenarioRefusesTheLog) {
  const std::string path =
      write(logEvent(0, "SCENARIO", std::string(static_cast<std::size_t>(maxScenarioEventBytes()) + 1, 'x')));
  try {
    readLog(path, [](const lcm::LogEvent&) { FAIL() << "an event was handed out"; });
    FAIL() << "the log was read";
  } catch (const LogError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  path + ": the SCENARIO at byte 0 holds " + std::to_string(maxScenarioEventBytes() + 1) +
                  " bytes; a scenario is at most " + std::to_string(maxScenarioEventBytes())),
              std::string::npos)
        << e.what();
  }
}

// What the project writes stays within the bounds: every golden log reads
// whole, nothing skipped, and bounded by its own scenario.
TEST(LogBounds, EveryGoldenLogReadsWholeWithinItsScenariosBounds) {
  for (const auto& entry : fs::directory_iterator(testing::kGoldenDir)) {
    SCOPED_TRACE(entry.path().string());
    const EventBounds bounds = boundsOfLog(entry.path().string());
    EXPECT_EQ(bounds.origin().rfind("the log's scenario (", 0), 0u) << bounds.origin();
    const LogScan scan = readLog(entry.path().string(), [](const lcm::LogEvent&) {});
    EXPECT_EQ(scan.oversized_events, 0);
    EXPECT_TRUE(scan.problems().empty());
  }
}

// A FIFO, a device, a directory and a link to a device are refused by what
// they are, before anything is read: the reader opens without blocking and
// looks at the descriptor it will read (no window between a look and an open).
TEST_F(LogBoundsTest, AFifoADeviceOrADirectoryIsRefusedByWhatItIs) {
  const std::string fifo = (dir_ / "fifo.lcm").string();
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string link = (dir_ / "zero.lcm").string();
  fs::create_symlink("/dev/zero", link);
  for (const auto& [path, kind] :
       std::vector<std::pair<std::string, std::string>>{{fifo, "a FIFO (named pipe)"},
                                                        {"/dev/urandom", "a character device"},
                                                        {link, "a character device"},
                                                        {dir_.string(), "a directory"}}) {
    try {
      readLog(path, [](const lcm::LogEvent&) {});
      ADD_FAILURE() << path << " was read";
    } catch (const LogError& e) {
      EXPECT_EQ(std::string(e.what()),
                "'" + path + "' is " + kind + "; expected an LCM log file (a regular file)");
    }
  }
}

}  // namespace
}  // namespace lagrange::logs
