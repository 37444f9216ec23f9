// `lagrange spy` for real: under a virtual display (Xvfb), `lagrange spy OUT`
// started first, as the README's tour types it, waits for the run; a
// realtime run in its own private network namespace then starts there, and
// lcm-spy on it is read back from a screenshot of its window by OCR
// (tesseract). The project's
// types must be decoded: lcm-spy reports finding them, and the Type column
// names them. A control run of the same lcm-spy without the project's types
// jar finds none, so the check can fail.
//
// LAGRANGE_SPY_SCREENSHOT=PATH keeps the screenshot (docs/lcm-spy.png is one).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <regex>
#include <sstream>

#include "support/child.hpp"
#include "support/help_examples.hpp"
#include "support/launch.hpp"
#include "support/wait.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;

// The lcm-spy table's Channel and Type columns as OCR reads them, lower-case letters only.
std::string readTypeColumn(const std::string& display, const std::string& dir, const std::string& tag) {
  const std::string shot = dir + "/" + tag + ".png", crop = dir + "/" + tag + "-crop.png";
  const RunResult grab = shell("import -window root -display " + display + " " + quote(shot));
  EXPECT_EQ(grab.exit_code, 0) << grab.output;
  shell("convert " + quote(shot) + " -crop 330x150+0+0 -resize 400% -colorspace Gray -threshold 60% " +
        quote(crop));
  const RunResult ocr = shell("tesseract " + quote(crop) + " - --psm 6 2>/dev/null");
  std::string letters;
  for (char c : ocr.output)
    if (std::isalpha(static_cast<unsigned char>(c))) letters += static_cast<char>(std::tolower(c));
  return letters;
}

int typesNamed(const std::string& letters) {
  int found = 0;
  // "_t" suffix included: channel names alone never match, hex ("?? 6e61...") has no 't'.
  for (const char* type :
       {"actuatorstatet", "controlcommandt", "plantpositiont", "planttrutht", "scenariot", "statust"})
    found += letters.find(type) != std::string::npos;
  return found;
}

TEST(Spy, ShowsTheProjectsMessagesDecodedOnARunInItsPrivateNamespace) {
  const std::string dir = freshDir("spy");
  fs::create_directories(dir);
  static std::mt19937 rng(std::random_device{}());
  std::string display;
  do display = ":" + std::to_string(100 + rng() % 800);
  while (fs::exists("/tmp/.X" + display.substr(1) + "-lock"));
  Child xvfb({"Xvfb", display, "-screen", "0", "800x600x24", "-nolisten", "tcp"}, dir + "/xvfb.log");
  ASSERT_TRUE(waitFor([&] { return fs::exists("/tmp/.X11-unix/X" + display.substr(1)); }, 10))
      << "Xvfb did not start: " << slurp(dir + "/xvfb.log");
  setenv("DISPLAY", display.c_str(), 1);

  const std::string run = dir + "/runs/live";
  std::unique_ptr<Child> scenario;
  std::string letters;
  {
    // The example `lagrange spy --help` ends with, typed in the run's folder
    // before the run: it waits, and says how to start one.
    const CommandHelp help = commandHelp("spy");
    ASSERT_EQ(help.examples, std::vector<std::string>{"lagrange spy runs/live"}) << help.text;
    Child spy(
        {"sh", "-c", "cd " + quote(dir) + " && PATH=" + quote(kBin) + ":\"$PATH\" exec " + help.examples[0]},
        dir + "/spy.out");
    ASSERT_TRUE(waitFor(
        [&] {
          return slurp(dir + "/spy.out")
                     .find(
                         "lagrange spy: waiting for a live run in runs/live (start one with: lagrange run "
                         "SCENARIO --mode realtime --out runs/live); Ctrl-C stops") != std::string::npos;
        },
        10))
        << slurp(dir + "/spy.out");
    EXPECT_TRUE(spy.running()) << slurp(dir + "/spy.out");
    // The run, long enough to watch, in its own network namespace (the default).
    scenario = std::make_unique<Child>(
        std::vector<std::string>{kBin + "/lagrange", "run",
                                 std::string(LAGRANGE_SOURCE_DIR) + "/configs/rigid_2dof.yaml", "-o", run,
                                 "--mode", "realtime", "--set", "duration=60", "-q"},
        dir + "/run.out");
    ASSERT_TRUE(waitFor([&] { return fs::exists(run + "/lcm.json"); }, 20)) << slurp(dir + "/run.out");
    ASSERT_TRUE(waitFor([&] { return slurp(dir + "/spy.out").find("LCM types") != std::string::npos; }, 30))
        << slurp(dir + "/spy.out");
    // Traffic fills the table: read it until four of the types show (a
    // screenshot and its OCR take about a second), for at most 20 s.
    waitFor([&] { return (letters = readTypeColumn(display, dir, "spy"), typesNamed(letters) >= 4); }, 20);
    EXPECT_TRUE(spy.running()) << slurp(dir + "/spy.out");
  }
  const std::string spy_out = slurp(dir + "/spy.out");
  int project_types = 0;  // one Java class per lcmtypes/*.lcm
  for (const auto& f : fs::directory_iterator(std::string(LAGRANGE_SOURCE_DIR) + "/lcmtypes"))
    project_types += f.path().extension() == ".lcm";
  EXPECT_NE(spy_out.find("Found " + std::to_string(project_types) + " LCM types"), std::string::npos)
      << "lcm-spy did not load the project's " << project_types << " types:\n"
      << spy_out;
  EXPECT_GE(typesNamed(letters), 4) << "OCR of the Type column: " << letters;
  if (const char* keep = std::getenv("LAGRANGE_SPY_SCREENSHOT"))
    fs::copy_file(dir + "/spy.png", keep, fs::copy_options::overwrite_existing);

  // Control: the same lcm-spy without the project's jar decodes nothing.
  {
    const RunResult command = lagrange("spy " + quote(run) + " --print-command");
    ASSERT_EQ(command.exit_code, 0) << command.output;
    std::string cmd = command.output;
    const auto jar = cmd.find(":" + kBin.substr(0, kBin.rfind('/')) + "/share/java/lagrange_lcmtypes.jar");
    ASSERT_NE(jar, std::string::npos) << cmd;
    cmd.erase(jar, cmd.find(' ', jar) - jar);
    cmd.erase(cmd.find_last_not_of("\n") + 1);
    // Inside the run's namespace, as lagrange spy does: nsenter with the launcher's pid.
    std::smatch pid;
    const std::string endpoint = slurp(run + "/lcm.json");
    ASSERT_TRUE(std::regex_search(endpoint, pid, std::regex("\"netns_pid\": *([0-9]+)"))) << endpoint;
    Child control({"nsenter", "--net=/proc/" + pid[1].str() + "/ns/net", "sh", "-c", cmd},
                  dir + "/control.out");
    ASSERT_TRUE(
        waitFor([&] { return slurp(dir + "/control.out").find("LCM types") != std::string::npos; }, 30))
        << slurp(dir + "/control.out");
    // Until the table lists the channels (its SCENARIO row read back), for at most 20 s.
    std::string control_letters;
    waitFor(
        [&] {
          control_letters = readTypeColumn(display, dir, "control");
          return control_letters.find("scenario") != std::string::npos;
        },
        20);
    EXPECT_NE(slurp(dir + "/control.out").find("Found 0 LCM types"), std::string::npos)
        << slurp(dir + "/control.out");
    EXPECT_EQ(typesNamed(control_letters), 0) << "OCR without the types jar: " << control_letters;
    EXPECT_NE(control_letters.find("scenario"), std::string::npos)  // the OCR did read the table
        << control_letters;
  }
  scenario->signal(SIGINT);
  EXPECT_GE(scenario->wait(30), 0);
}

// Without Xvfb or a run: a folder that never holds a run is named when the
// wait ends -- what it is, what was expected, the wait -- not CLI11's "run:
// Directory does not exist"; without a display spy says so before waiting.
TEST(SpyFolder, AMissingRunFolderIsNamedWithWhatWasExpected) {
  const std::string dir = freshDir("spy-folder");
  fs::create_directories(dir);
  const RunResult r =
      shell("cd " + quote(dir) + " && DISPLAY=:9 " + kBin + "/lagrange spy runs/live --wait 0.5");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("lagrange spy: waiting for a live run in runs/live"), std::string::npos)
      << r.output;
  EXPECT_NE(
      r.output.find("lagrange spy: the run folder runs/live does not exist; expected the output folder of a "
                    "running `lagrange run SCENARIO --mode realtime --out runs/live` (waited 0.5 s: --wait)"),
      std::string::npos)
      << r.output;
  const RunResult headless =
      shell("cd " + quote(dir) + " && env -u DISPLAY " + kBin + "/lagrange spy runs/live");
  EXPECT_EQ(headless.exit_code, 2) << headless.output;
  EXPECT_NE(headless.output.find("DISPLAY is not set"), std::string::npos) << headless.output;
  EXPECT_EQ(headless.output.find("waiting"), std::string::npos) << headless.output;
}

}  // namespace
}  // namespace lagrange::testing
