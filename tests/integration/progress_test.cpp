// The progress display of lagrange run: plain lines every 2 s when stdout is
// not a terminal (CI logs), a bar redrawn in place on a terminal (a pty from
// script(1)); both show sim time, the real-time factor and the tracking error.
#include <gtest/gtest.h>

#include <regex>

#include "support/configs.hpp"
#include "support/launch.hpp"

namespace lagrange::testing {
namespace {

TEST(Progress, PlainLinesWhenNotATerminal) {
  // Realtime: 3 s of wall time, so lines at about 0 s and 2 s, and the final one.
  const RunResult r = runScenario(kRigid, freshDir("progress-plain"), "--mode realtime --set duration=3");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::regex line(
      R"(progress: t = [0-9]+\.[0-9]{2} / 3\.00 s \( *[0-9]+%\), [0-9.]+x real time, \|q~\| = (--|[0-9.]+e[-+][0-9]+ rad))");
  const auto count =
      std::distance(std::sregex_iterator(r.output.begin(), r.output.end(), line), std::sregex_iterator());
  EXPECT_GE(count, 2) << r.output;
  // The last line is the final sample, at about real time (counted from the first sample).
  EXPECT_TRUE(std::regex_search(
      r.output, std::regex(R"(progress: t = 3\.00 / 3\.00 s \(100%\), (0\.9|1\.0|1\.1)x real time)")))
      << r.output;
  EXPECT_EQ(r.output.find('\r'), std::string::npos) << "carriage returns in a non-terminal output";
}

TEST(Progress, ABarOnATerminal) {
  const std::string out = freshDir("progress-tty");
  const RunResult r =
      shell("script -qec " +
            quote(kBin + "/lagrange run " + kRigid + " -o " + out + " --mode realtime --set duration=2") +
            " /dev/null");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::regex_search(
      r.output,
      std::regex(
          R"(\r\[#{30}\] t = +2\.00 / 2\.00 s +(0\.9|1\.0|1\.1)x real time  \|q~\| = [0-9.]+e-0[0-9] rad)")))
      << r.output;
  const auto redraws = std::count(r.output.begin(), r.output.end(), '\r');
  EXPECT_GE(redraws, 10) << "the bar is redrawn every 100 ms";
  EXPECT_EQ(r.output.find("progress: t ="), std::string::npos) << r.output;
}

}  // namespace
}  // namespace lagrange::testing
