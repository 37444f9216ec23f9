// A controller from outside the project (controller.type external): the Java
// PD of examples/external_controller/, compiled here with javac and never by
// CMake, takes the controller's place over the LCM contract of
// docs/external_programs.md -- in lockstep and in realtime -- and its runs
// replay: `lagrange replay LOG -- COMMAND` runs the program named after --
// (never the command the log holds) on the recorded positions and gets every
// recorded command back bit for bit.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/launch.hpp"
#include "support/run_log.hpp"
#include "support/sweep_files.hpp"
#include "support/wait.hpp"

namespace lagrange::testing {
namespace {

const std::string kClassPath =
    std::string("/usr/share/java/lcm.jar:") + LAGRANGE_BIN_DIR + "/../share/java/lagrange_lcmtypes.jar";

// The PD's class directory, compiled once for the tests here.
const std::string& pdClasses() {
  static const std::string dir = [] {
    const std::string out = freshDir("external-pd-classes");
    const RunResult r =
        shell("javac -cp " + kClassPath + " -d " + quote(out) + " " +
              quote(std::string(LAGRANGE_SOURCE_DIR) + "/examples/external_controller/PdController.java"));
    if (r.exit_code != 0) throw std::runtime_error("javac failed: " + r.output);
    return out;
  }();
  return dir;
}

// The Pelican without gravity, regulated by the external PD to a constant q_d.
const Eigen::Vector2d kKp(20.0, 5.0), kKd(4.0, 1.0), kQd(0.5, -0.2);
const std::string kPdArguments = "--kp, \"20,5\", --kd, \"4,1\", --qd, \"0.5,-0.2\"";
std::string javaCommand() { return "java, -cp, \"" + pdClasses() + ":" + kClassPath + "\", PdController"; }
// The Python PD of examples/external_controller/, with python/ on PYTHONPATH
// by the scenario's environment and -S: no site-packages, so no numpy.
std::string pythonCommand() {
  return "env, \"PYTHONPATH=" + std::string(LAGRANGE_SOURCE_DIR) + "/python\", python3, -S, \"" +
         LAGRANGE_SOURCE_DIR + "/examples/external_controller/pd_controller.py\"";
}
// The same commands as replay takes them, after -- (argv words, shell-quoted).
std::string javaReplayCommand(const std::string& kp = "20,5") {
  return " -- java -cp " + quote(pdClasses() + ":" + kClassPath) + " PdController --kp " + quote(kp) +
         " --kd 4,1 --qd 0.5,-0.2";
}
std::string pythonReplayCommand() {
  return " -- env " + quote("PYTHONPATH=" + std::string(LAGRANGE_SOURCE_DIR) + "/python") + " python3 -S " +
         quote(std::string(LAGRANGE_SOURCE_DIR) + "/examples/external_controller/pd_controller.py") +
         " --kp 20,5 --kd 4,1 --qd 0.5,-0.2";
}
std::string scenario(const std::string& mode, const std::string& command = javaCommand(),
                     const std::string& arguments = kPdArguments) {
  const std::string path = freshDir("external-config") + ".yaml";
  std::ofstream(path)
      << "name: external_pd\nduration: 3.0\nmode: " << mode
      << "\nrobot: {preset: pelican, gravity: 0.0}\n"
         "initial_state: {q: [0.2, -0.1], qdot: [0.0, 0.0]}\n"
         "reference: {type: sine, offset: [0.5, -0.2], amplitude: [0.0, 0.0], frequency: [0.0, 0.0]}\n"
         "plant: {physics_step: 1.0e-4, publish_rate: 1000}\n"
         "controller:\n  type: external\n  command: ["
      << command << ", " << arguments
      << "]\n"
         "metrics: {tolerance: 1.0e-3, convergence_deadline: 2.0}\n";
  return path;
}

// The report's TIMING.csv (a realtime run with --report): every latency from
// a position's publish_utime to the command and the actuator state answering
// it is >= 0 -- each process stamps the run's clock (transport/run_clock.hpp),
// the external program too, from LAGRANGE_CLOCK_OFFSET_US.
void expectLatenciesNeverNegative(const std::string& out) {
  std::ifstream timing(out + "/report/TIMING.csv");
  std::string line;
  ASSERT_TRUE(std::getline(timing, line)) << "no " << out << "/report/TIMING.csv";
  ASSERT_EQ(line, "tick,period_error_us,command_latency_us,actuator_latency_us");
  long long rows = 0, negative = 0;
  while (std::getline(timing, line)) {
    std::stringstream fields(line);
    std::string tick, period, command, actuator;
    std::getline(fields, tick, ',');
    std::getline(fields, period, ',');
    std::getline(fields, command, ',');
    std::getline(fields, actuator, ',');
    if (command.empty() || actuator.empty()) continue;
    ++rows;
    if (std::stoll(command) < 0 || std::stoll(actuator) < 0) ++negative;
  }
  EXPECT_GT(rows, 2000);
  EXPECT_EQ(negative, 0) << "latencies below zero in " << out << "/report/TIMING.csv";
}

// Every command of a log is the PD law on the positions it answered, where
// the controller also answered the tick before (its velocity's difference).
void expectThePdLaw(const std::string& log) {
  const auto positions = readPositions(log);
  const auto commands = readCommands(log);
  ASSERT_GT(commands.size(), 2000u);
  size_t checked = 0;
  for (const auto& [k, u] : commands) {
    if (k == 0 || !commands.count(k - 1)) continue;
    for (int i = 0; i < 2; ++i) {
      const double q = positions.at(k)[i], v = (q - positions.at(k - 1)[i]) / 1e-3;
      EXPECT_NEAR(u[i], -kKp(i) * (q - kQd(i)) - kKd(i) * v, 1e-9) << "tick " << k;
    }
    ++checked;
  }
  EXPECT_GT(checked, 2000u);
}

TEST(ExternalController, AJavaPdTakesTheControllersPlaceInLockstepAndItsRunReplays) {
  const std::string out = freshDir("external-lockstep");
  const RunResult run = runScenario(scenario("lockstep"), out, "");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("gain conditions NOT CHECKED: external controller (java)"), std::string::npos)
      << run.output;
  const auto j = readSummary(out);
  EXPECT_TRUE(j["tracking"]["met"].get<bool>()) << j["tracking"].dump();
  // Every command is the PD law on the positions it answered, as written here.
  EXPECT_EQ(readCommands(out + "/run.lcm").size(), 3001u);
  expectThePdLaw(out + "/run.lcm");
  for (const std::string component : {"controller", "actuator", "plant"}) {
    const RunResult replay = lagrange("replay " + quote(out + "/run.lcm") + " --component " + component +
                                      (component == "controller" ? javaReplayCommand() : ""));
    EXPECT_EQ(replay.exit_code, 0) << component << ": " << replay.output;
    EXPECT_NE(replay.output.find("reproduced all 3001 recorded outputs"), std::string::npos) << replay.output;
  }
  // A changed gain is caught: the replayed controller is the program named after --.
  const RunResult changed = lagrange("replay " + quote(out + "/run.lcm") + javaReplayCommand("21,5"));
  EXPECT_EQ(changed.exit_code, 1) << changed.output;
  EXPECT_NE(changed.output.find("DIVERGED after 1 outputs at tick 0"), std::string::npos) << changed.output;
  // A law that returns NaN is stopped at the Java SDK, naming the value, the
  // joint and the sample (issue #46), as the C++ and Python SDKs do.
  const std::string nan = freshDir("external-java-nan");
  const RunResult bad =
      runScenario(scenario("lockstep", javaCommand(), "--kp, \"NaN,5\", --kd, \"4,1\", --qd, \"0.5,-0.2\""),
                  nan, "-q --set duration=0.5");
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  const std::string said = readText(nan + "/controller.log");
  EXPECT_NE(said.find("the law returned NaN for u[0] (joint 1) at the sample of tick 0 (t = 0.0 s); expected "
                      "finite numbers"),
            std::string::npos)
      << said;
}

TEST(ExternalController, AJavaPdRunsInRealtimeAndItsRunReplays) {
  const std::string out = freshDir("external-realtime");
  const RunResult run = runScenario(scenario("realtime"), out, "-q --report");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  // The program publishes no STATUS, so its commands cannot be counted
  // against a published total; convergence shows it answered, and how many
  // ticks it answered depends on the machine's load, so no count is asserted.
  EXPECT_TRUE(readSummary(out)["tracking"]["met"].get<bool>());
  expectLatenciesNeverNegative(out);
  const RunResult replay =
      lagrange("replay " + quote(out + "/run.lcm") + " --component controller" + javaReplayCommand());
  EXPECT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_NE(replay.output.find("reproduced all"), std::string::npos) << replay.output;
}

}  // namespace
}  // namespace lagrange::testing

namespace lagrange::testing {
namespace {

// The Python PD (python/lagrange/external.py keeps the contract) in lockstep:
// the same run as the Java PD's, every sample bit for bit, and it replays.
TEST(ExternalController, APythonPdMatchesTheJavaOneBitForBitInLockstepAndReplays) {
  const std::string java = freshDir("external-java"), python = freshDir("external-python");
  ASSERT_EQ(runScenario(scenario("lockstep"), java, "-q").exit_code, 0);
  const RunResult run = runScenario(scenario("lockstep", pythonCommand()), python, "-q");
  ASSERT_EQ(run.exit_code, 0) << run.output << readText(python + "/controller.log");
  EXPECT_TRUE(readSummary(python)["tracking"]["met"].get<bool>());
  const auto a = readTruth(java + "/run.lcm"), b = readTruth(python + "/run.lcm");
  ASSERT_EQ(a.size(), 3001u);
  ASSERT_EQ(b.size(), a.size());
  for (size_t k = 0; k < a.size(); ++k) {
    ASSERT_LE((a[k].q - b[k].q).cwiseAbs().maxCoeff(), 1e-9) << "tick " << k;
    ASSERT_LE((a[k].qdot - b[k].qdot).cwiseAbs().maxCoeff(), 1e-9) << "tick " << k;
  }
  EXPECT_EQ(readCommands(java + "/run.lcm"), readCommands(python + "/run.lcm"));
  expectThePdLaw(python + "/run.lcm");
  const RunResult replay = lagrange("replay " + quote(python + "/run.lcm") + pythonReplayCommand());
  EXPECT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_NE(replay.output.find("reproduced all 3001 recorded outputs bit for bit"), std::string::npos)
      << replay.output;

  // lagrange.log.load, without numpy, reads the run as the C++ reader does:
  // the samples, their values (repr: every bit) and every checksum intact.
  const RunResult loaded =
      shell("PYTHONPATH=" + quote(std::string(LAGRANGE_SOURCE_DIR) + "/python") +
            " python3 -S -c 'import sys, lagrange.log as L; r = L.load(sys.argv[1]); "
            "t = r.channels[\"PLANT_TRUTH\"]; c = r.channels[\"CONTROL_COMMAND\"]; "
            "print(len(t[\"t\"]), len(c[\"u\"]), repr(t[\"q\"][1234][1]), repr(c[\"u\"][2999][0]), "
            "sum(r.corrupt.values()), sum(r.undecodable.values()), r.summary[\"tracking\"][\"met\"])' " +
            quote(python));
  ASSERT_EQ(loaded.exit_code, 0) << loaded.output;
  char expected[256];
  std::snprintf(expected, sizeof expected, "3001 3001 %.17g %.17g 0 0 True\n", b[1234].q(1),
                readCommands(python + "/run.lcm").at(2999)[0]);
  EXPECT_EQ(loaded.output, expected);
}

// A program that reads its parameters from the run's scenario (the Python
// PD without --qd takes q_d from reference.offset, through
// lagrange.external.scenario(): LAGRANGE_CONFIG_JSON) runs as the one given
// q_d on its command line, and replays: replay hands it the log's scenario
// and the rest of a run's environment, and says so.
TEST(ExternalController, AProgramThatReadsTheScenarioRunsAndReplaysWithIt) {
  const std::string given = freshDir("external-python-qd"), read = freshDir("external-python-scenario");
  ASSERT_EQ(runScenario(scenario("lockstep", pythonCommand()), given, "-q --set duration=1").exit_code, 0);
  const RunResult run = runScenario(scenario("lockstep", pythonCommand(), "--kp, \"20,5\", --kd, \"4,1\""),
                                    read, "-q --set duration=1");
  ASSERT_EQ(run.exit_code, 0) << run.output << readText(read + "/controller.log");
  EXPECT_EQ(readCommands(given + "/run.lcm"), readCommands(read + "/run.lcm"));
  // The run's scenario as JSON: numbers as numbers, strings as strings.
  const auto resolved = nlohmann::json::parse(slurp(read + "/config.resolved.json"));
  EXPECT_EQ(resolved["reference"]["offset"], nlohmann::json::array({0.5, -0.2})) << resolved.dump();
  EXPECT_EQ(resolved["plant"]["physics_step"], 1e-4) << resolved.dump();
  EXPECT_EQ(resolved["controller"]["type"], "external") << resolved.dump();
  const RunResult replay =
      lagrange("replay " + quote(read + "/run.lcm") + " -- env " +
               quote("PYTHONPATH=" + std::string(LAGRANGE_SOURCE_DIR) + "/python") + " python3 -S " +
               quote(std::string(LAGRANGE_SOURCE_DIR) + "/examples/external_controller/pd_controller.py") +
               " --kp 20,5 --kd 4,1");
  EXPECT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_NE(replay.output.find("reproduced all 1001 recorded outputs bit for bit"), std::string::npos)
      << replay.output;
  EXPECT_NE(
      replay.output.find("with a run's environment: LAGRANGE_LCM_URL, LAGRANGE_RUN_ID, LAGRANGE_KEY_FILE"),
      std::string::npos)
      << replay.output;
}

// In realtime: it answers the positions as they come, obeys the law, and its
// run replays bit for bit.
TEST(ExternalController, APythonPdRunsInRealtimeAndItsRunReplays) {
  const std::string out = freshDir("external-python-realtime");
  const RunResult run = runScenario(scenario("realtime", pythonCommand()), out, "-q --report");
  ASSERT_EQ(run.exit_code, 0) << run.output << readText(out + "/controller.log");
  const auto summary = readSummary(out);
  EXPECT_TRUE(summary["tracking"]["met"].get<bool>());
  // A loop like the others (issue #46): the scheduling the launcher gave it
  // (the built-in loops' own, or the normal scheduler where SCHED_FIFO is
  // not allowed, as theirs), its timing from its commands' arrivals, and
  // what it published counted by its receivers.
  const auto& loop = summary["timing"]["loops"]["controller"];
  ASSERT_TRUE(loop.is_object()) << summary["timing"].dump();
  // One priority below the built-in loops (or, as theirs, the normal scheduler).
  const std::string actuator = summary["timing"]["loops"]["actuator"]["scheduler"];
  EXPECT_EQ(loop["scheduler"], actuator.rfind("fifo:", 0) == 0
                                   ? "fifo:" + std::to_string(std::stoi(actuator.substr(5)) - 1)
                                   : actuator)
      << loop.dump();
  EXPECT_GE(loop["cycles"].get<long long>(), 2000) << loop.dump();  // of 3001: it answered, period by period
  EXPECT_NEAR(loop["achieved_rate"].get<double>(), 1000.0, 350.0)
      << loop.dump();  // >= 2000 of 3001 allows 667
  EXPECT_NE(loop["measured_by"].get<std::string>().find("arrivals of CONTROL_COMMAND"), std::string::npos);
  EXPECT_GE(summary["messages"]["CONTROL_COMMAND"]["published"].get<long long>(), 2000);
  EXPECT_GE(summary["answers"]["controller"]["answered"].get<long long>(), 2000) << summary["answers"].dump();
  expectLatenciesNeverNegative(out);
  expectThePdLaw(out + "/run.lcm");
  const RunResult replay = lagrange("replay " + quote(out + "/run.lcm") + pythonReplayCommand());
  EXPECT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_NE(replay.output.find("reproduced all"), std::string::npos) << replay.output;
}

// `lagrange compare`: external programs are rows like any controller (a
// compare.controllers entry with type external names the row), run in
// lockstep beside the built-in ones in process. The Java and the Python PD
// give the same row, number for number.
TEST(ExternalController, CompareRunsExternalProgramsAsRows) {
  const std::string dir = freshDir("external-compare");
  std::filesystem::create_directories(dir);
  std::string text = readText(scenario("lockstep", pythonCommand()));
  text = text.substr(0, text.find("controller:")) +
         "controller: {type: theorem1, kp: [20, 5], kd: [4, 1], a: [50, 50], b: [50, 50]}\n"
         "metrics: {tolerance: 1.0e-3, convergence_deadline: 2.0}\n"
         "compare:\n  controllers:\n"
         "    pd_python: {type: external, command: [" +
         pythonCommand() + ", " + kPdArguments + "]}\n    pd_java: {type: external, command: [" +
         javaCommand() + ", " + kPdArguments + "]}\n";
  std::ofstream(dir + "/compare.yaml") << text;
  const RunResult r = lagrange("compare " + quote(dir + "/compare.yaml") + " -o " + quote(dir + "/out") +
                               " --controllers theorem1,pd_python,pd_java");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto row = [&](const std::string& name) {
    const size_t at = r.output.find("| " + name + " | ");
    return at == std::string::npos
               ? std::string()
               : r.output.substr(at + name.size() + 3, r.output.find('\n', at) - at - name.size() - 3);
  };
  // The verdict cell may carry a warning of one program's own (a JVM or a
  // Python slow to give its first answer on a loaded machine); the numbers
  // after it are the runs', and must be the same.
  const auto numbers = [&](const std::string& name) {
    const std::string cells = row(name);
    const size_t at = cells.find(" | 1.05 |");
    return at == std::string::npos ? std::string() : cells.substr(at);
  };
  EXPECT_NE(row("theorem1"), "") << r.output;
  EXPECT_EQ(row("pd_python").rfind("| completed | met", 0), 0u) << r.output;
  EXPECT_EQ(row("pd_java").rfind("| completed | met", 0), 0u) << r.output;
  EXPECT_NE(numbers("pd_python"), "") << r.output;
  EXPECT_EQ(numbers("pd_python"), numbers("pd_java")) << r.output;
  EXPECT_EQ(readSummary(dir + "/out/runs/pd_python")["mode"], "lockstep");
  EXPECT_EQ(readCommands(dir + "/out/runs/pd_python/run.lcm"),
            readCommands(dir + "/out/runs/pd_java/run.lcm"));
}

// `lagrange sweep` over an external controller: each row is a lockstep run
// of the program, the same to the last bit as `lagrange run` with the row's
// overrides.
TEST(ExternalController, SweepRunsAnExternalProgramPerRow) {
  const std::string dir = freshDir("external-sweep");
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/sweep.yaml")
      << "scenario: " << scenario("lockstep", pythonCommand())
      << "\nset: {duration: 2}\n"
         "axes:\n  - {key: initial_state.q, values: [[0.2, -0.1], [1.0, 1.0]]}\n";
  const RunResult r = lagrange("sweep " + quote(dir + "/sweep.yaml") + " -o " + quote(dir + "/out") + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream rows(dir + "/out/sweep.jsonl");
  std::string line;
  std::getline(rows, line);
  std::getline(rows, line);  // row 1: from (1, 1)
  const auto row = nlohmann::json::parse(line);
  EXPECT_EQ(row.at("status"), "completed") << line;
  // Each completed row's run directory is removed, and OUT/external/ with them.
  EXPECT_FALSE(std::filesystem::exists(dir + "/out/external")) << "left behind, empty";
  const std::string direct = freshDir("external-sweep-direct");
  ASSERT_EQ(runScenario(scenario("lockstep", pythonCommand()), direct,
                        "-q --set duration=2 --set 'initial_state.q=[1.0, 1.0]'")
                .exit_code,
            0);
  const auto summary = readSummary(direct);
  EXPECT_EQ(row.at("final_error").get<double>(), summary["tracking"]["final_error"].get<double>());
  EXPECT_EQ(row.at("convergence_time").get<double>(), summary["tracking"]["convergence_time"].get<double>());
  EXPECT_EQ(row.at("gains_checked"), false);
}

// The C++ SDK from outside the tree: `cmake --install` of this build, then
// examples/cpp_controller configured with find_package(lagrange) against
// the installed package, built, and run as the controller: its lockstep run
// is the Java PD's, command for command, and the installed `lagrange` runs it.
TEST(ExternalController, ACppPdBuiltAgainstTheInstalledPackageMatchesTheJavaOne) {
  const std::string prefix = freshDir("cpp-sdk-install"), build = freshDir("cpp-sdk-build");
  const std::string tree = std::string(LAGRANGE_BIN_DIR) + "/..";
  const RunResult install = shell("cmake --install " + quote(tree) + " --prefix " + quote(prefix) + " 2>&1");
  ASSERT_EQ(install.exit_code, 0) << install.output;
  for (const char* file :
       {"/include/lagrange/sdk/external_controller.hpp", "/include/lagrange/plant_position_t.hpp",
        "/lib/cmake/lagrange/lagrangeConfig.cmake", "/bin/lagrange"})
    EXPECT_TRUE(std::filesystem::exists(prefix + file)) << file;
  const RunResult configure =
      shell("cmake -S " + quote(std::string(LAGRANGE_SOURCE_DIR) + "/examples/cpp_controller") + " -B " +
            quote(build) + " -DCMAKE_PREFIX_PATH=" + quote(prefix) + " 2>&1 && cmake --build " +
            quote(build) + " 2>&1");
  ASSERT_EQ(configure.exit_code, 0) << configure.output;

  const std::string java = freshDir("cpp-sdk-java"), cpp = freshDir("cpp-sdk-cpp");
  ASSERT_EQ(runScenario(scenario("lockstep"), java, "-q").exit_code, 0);
  const RunResult run =
      shell(quote(prefix + "/bin/lagrange") + " run " +
            quote(scenario("lockstep", quote(build + "/pd_controller"))) + " -q -o " + quote(cpp) + " 2>&1");
  ASSERT_EQ(run.exit_code, 0) << run.output << readText(cpp + "/controller.log");
  EXPECT_TRUE(readSummary(cpp)["tracking"]["met"].get<bool>());
  EXPECT_EQ(readCommands(java + "/run.lcm"), readCommands(cpp + "/run.lcm"));
  expectThePdLaw(cpp + "/run.lcm");
  const RunResult replay = lagrange("replay " + quote(cpp + "/run.lcm") + " -- " +
                                    quote(build + "/pd_controller") + " --kp 20,5 --kd 4,1 --qd 0.5,-0.2");
  EXPECT_EQ(replay.exit_code, 0) << replay.output;

  // Without --qd the program reads q_d from the scenario the run hands over
  // (lagrange::sdk::scenario(), issue #46): the same commands, and replay
  // hands the same scenario over.
  const std::string from_scenario = freshDir("cpp-sdk-scenario");
  const RunResult reading =
      shell(quote(prefix + "/bin/lagrange") + " run " +
            quote(scenario("lockstep", quote(build + "/pd_controller"), "--kp, \"20,5\", --kd, \"4,1\"")) +
            " -q -o " + quote(from_scenario) + " 2>&1");
  ASSERT_EQ(reading.exit_code, 0) << reading.output << readText(from_scenario + "/controller.log");
  EXPECT_EQ(readCommands(from_scenario + "/run.lcm"), readCommands(cpp + "/run.lcm"));
  const RunResult replay_reading = lagrange("replay " + quote(from_scenario + "/run.lcm") + " -- " +
                                            quote(build + "/pd_controller") + " --kp 20,5 --kd 4,1");
  EXPECT_EQ(replay_reading.exit_code, 0) << replay_reading.output;

  // A law that returns NaN is stopped at the SDK, naming the value, the joint
  // and the sample, rather than left for the plant to refuse and stall on.
  const std::string nan = freshDir("cpp-sdk-nan");
  const RunResult bad = shell(quote(prefix + "/bin/lagrange") + " run " +
                              quote(scenario("lockstep", quote(build + "/pd_controller"),
                                             "--kp, \"nan,5\", --kd, \"4,1\", --qd, \"0.5,-0.2\"")) +
                              " -q -o " + quote(nan) + " --set duration=0.5 2>&1");
  EXPECT_NE(bad.exit_code, 0) << bad.output;
  const std::string said = readText(nan + "/controller.log");
  EXPECT_NE(
      said.find("nan for u[0] (joint 1) at the sample of tick 0 (t = 0.000000 s); expected finite numbers"),
      std::string::npos)
      << said;
}

}  // namespace
}  // namespace lagrange::testing
