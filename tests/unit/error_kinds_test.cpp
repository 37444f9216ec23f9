// One error root (util/error.hpp): each component's error has a kind, and the
// exit code comes from the kind alone (exitCodeOf), whatever command catches it.
#include <gtest/gtest.h>

#include <new>
#include <sstream>
#include <stdexcept>

#include "config/scenario.hpp"
#include "logs/log_event_reader.hpp"
#include "plant/plant_sim.hpp"
#include "plant/stall_diagnosis.hpp"
#include "tools/command_error.hpp"
#include "tools/replay/replay.hpp"
#include "tools/report/plots.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"

namespace lagrange {
namespace {

TEST(ErrorKinds, BadInputOfEveryComponentExitsTwo) {
  EXPECT_EQ(exitCodeOf(BadInput("x")), kExitBadInput);
  EXPECT_EQ(exitCodeOf(config::ConfigError("controller.kp: expected > 0")), kExitBadInput);
  EXPECT_EQ(exitCodeOf(logs::LogError("not an LCM log")), kExitBadInput);
  EXPECT_EQ(exitCodeOf(tools::ReplayError("no SCENARIO")), kExitBadInput);
  EXPECT_EQ(exitCodeOf(util::UnsafeOutputPath("a symbolic link")), kExitBadInput);
}

TEST(ErrorKinds, RuntimeFaultsAndAnythingElseExitOne) {
  EXPECT_EQ(exitCodeOf(RuntimeFault("x")), kExitFailed);
  EXPECT_EQ(exitCodeOf(plant::PlantStopped("non-finite state")), kExitFailed);
  EXPECT_EQ(exitCodeOf(plant::PlantStalled("no answer")), kExitFailed);
  EXPECT_EQ(exitCodeOf(tools::PlotError("no gnuplot")), kExitFailed);
  // Replaying an external controller that dies is a fault, not a bad log.
  EXPECT_EQ(exitCodeOf(tools::ReplayError("the external controller died", {}, ErrorKind::kRuntimeFault)),
            kExitFailed);
  // A core's broken precondition or the system out of memory is no user's
  // input: a bug or a fault, never "bad input".
  EXPECT_EQ(exitCodeOf(std::invalid_argument("sizes differ")), kExitFailed);
  EXPECT_EQ(exitCodeOf(std::bad_alloc()), kExitFailed);
}

TEST(ErrorKinds, KindSurvivesCatchingByTheRoot) {
  try {
    throw config::ConfigError("bad key");
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kBadInput);
  }
  try {
    throw plant::PlantStopped("max_rate crossed");
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kRuntimeFault);
  }
}

TEST(ErrorKinds, FailWithNamesTheCommandAndReturnsTheKindsCode) {
  std::ostringstream captured;
  std::streambuf* const old = std::cerr.rdbuf(captured.rdbuf());
  const int bad = tools::failWith("lagrange report", logs::LogError("run.lcm: not an LCM log"));
  const int fault =
      tools::failWith("lagrange run", RuntimeFault("writing 'x' failed: No space left on device"));
  std::cerr.rdbuf(old);
  EXPECT_EQ(bad, kExitBadInput);
  EXPECT_EQ(fault, kExitFailed);
  EXPECT_EQ(captured.str(),
            "lagrange report: run.lcm: not an LCM log\n"
            "lagrange run: writing 'x' failed: No space left on device\n");
}

}  // namespace
}  // namespace lagrange
