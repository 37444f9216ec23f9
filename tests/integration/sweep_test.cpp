// `lagrange sweep` (docs/sweeps.md): the same sweep gives the same table on
// one core or two; a sweep killed midway and started again runs only the rows
// it had not finished and ends with the same table; a bad sweep file is named
// before anything runs.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <thread>

#include "support/child.hpp"
#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/sweep_files.hpp"
#include "transport/message_auth.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;

// A sweep of the default scenario, shortened: two gains by three initial
// errors (10 mrad to 10 rad) in two directions.
std::string writeSweep(const std::string& dir, const std::string& extra = "", double duration = 1.0) {
  fs::create_directories(dir);
  const std::string path = dir + "/sweep.yaml";
  std::ofstream(path)
      << "scenario: " << kConfigs << "/rigid_2dof.yaml\n"
      << "set: {duration: " << duration << "}\nseed: 4\n"
      << "axes:\n"
      << "  - {key: controller.kd, values: [5, 20]}\n"
      << "  - {key: initial_state.q, norm: {from: 0.01, to: 10, count: 3, scale: log}, directions: 2}\n"
      << extra;
  return path;
}

size_t tableRows(const std::string& out) {
  std::ifstream in(out + "/sweep.csv");
  size_t n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n - 1;
}

// A sweep of one axis: no heat map (it needs two), no margin map (the gains
// do not vary, so neither does the margin) -- each named with its reason in
// the output and in maps.gp, rather than left out without a word.
TEST(Sweep, SaysWhichMapsItDidNotDrawAndWhy) {
  const std::string dir = freshDir("sweep-maps-not-drawn");
  fs::create_directories(dir);
  std::ofstream(dir + "/sweep.yaml")
      << "scenario: " << kConfigs << "/rigid_2dof.yaml\n"
      << "set: {duration: 0.3}\n"
      << "axes:\n  - {key: initial_state.q, norm: {from: 0.01, to: 1, count: 3}}\n";
  const RunResult r = lagrange("sweep " + quote(dir + "/sweep.yaml") + " -o " + quote(dir + "/out"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("map not drawn: heat_map.png: the sweep has 1 axis; a heat map needs two"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("map not drawn: margin.png: every run has the same gain margin"), std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::exists(dir + "/out/maps/convergence_time.png"));
  EXPECT_FALSE(fs::exists(dir + "/out/maps/heat_map.png"));
  EXPECT_FALSE(fs::exists(dir + "/out/maps/margin.png"));
  const std::string maps = readText(dir + "/out/maps/maps.gp");
  EXPECT_NE(maps.find("# not drawn: heat_map.png"), std::string::npos) << maps;
  EXPECT_NE(maps.find("# not drawn: margin.png"), std::string::npos) << maps;
}

TEST(Sweep, TheSameSweepGivesTheSameTableOnOneCoreOrTwo) {
  const std::string dir = freshDir("sweep-determinism");
  const std::string sweep = writeSweep(dir);
  const RunResult one = lagrange("sweep " + quote(sweep) + " -o " + quote(dir + "/one") + " -j 1");
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const RunResult two = lagrange("sweep " + quote(sweep) + " -o " + quote(dir + "/two") + " -j 2 -q");
  ASSERT_EQ(two.exit_code, 0) << two.output;
  EXPECT_TRUE(two.output.empty()) << two.output;
  EXPECT_NE(one.output.find("12 of 12 runs in"), std::string::npos) << one.output;

  ASSERT_EQ(tableRows(dir + "/one"), 12u);
  EXPECT_EQ(tableWithoutWallTime(dir + "/one"), tableWithoutWallTime(dir + "/two"));
  EXPECT_EQ(readText(dir + "/one/sweep.jsonl").size() > 0, true);
  // One shard wrote every row of the first; two shards split the second.
  EXPECT_EQ(rowLines(dir + "/one").size(), 12u);
  EXPECT_TRUE(fs::exists(dir + "/two/rows/shard-1-of-2.jsonl"));
  for (const std::string png : {"convergence_time.png", "heat_map.png", "margin.png"})
    EXPECT_GT(fs::file_size(dir + "/one/maps/" + png), 5000u) << png;
  // The convergence map is drawn against the axis swept over the most values
  // (the initial error's norm), not ||x(0)||.
  const std::string maps = readText(dir + "/one/maps/maps.gp");
  EXPECT_NE(maps.find("set xlabel 'initial_state.q.norm"), std::string::npos) << maps;
  EXPECT_NE(one.output.find("map not drawn: region_vs_rate.png: plant.publish_rate is not swept"),
            std::string::npos)
      << one.output;

  // A row is the run: `lagrange run --mode inproc` with the row's overrides
  // (plan.json) ends with the same error, to the last bit.
  std::ifstream plan(dir + "/one/plan.json");
  std::string line;
  std::getline(plan, line);                                // the header
  for (int i = 0; i <= 10; ++i) std::getline(plan, line);  // row 10: kd 20, 10 rad
  const auto planned = nlohmann::json::parse(line);
  ASSERT_EQ(planned.at("index"), 10);
  std::string sets;
  for (const auto& ov : planned.at("overrides")) sets += " --set " + quote(ov.get<std::string>());
  const std::string direct = dir + "/direct";
  ASSERT_EQ(runScenario(kConfigs + "/rigid_2dof.yaml", direct, "-q --mode inproc" + sets).exit_code, 0);
  const auto summary = nlohmann::json::parse(readText(direct + "/summary.json"));
  nlohmann::json row;
  std::ifstream rows(dir + "/one/sweep.jsonl");
  for (int i = 0; i <= 10; ++i) std::getline(rows, line);
  row = nlohmann::json::parse(line);
  ASSERT_EQ(row.at("index"), 10);
  EXPECT_EQ(row.at("final_error").get<double>(), summary["tracking"]["final_error"].get<double>());
  EXPECT_EQ(row.at("max_error").get<double>(), summary["tracking"]["max_error"].get<double>());
  EXPECT_EQ(row.at("converged").get<bool>(), !summary["tracking"]["convergence_time"].is_null());
  EXPECT_EQ(row.at("gain_margin").get<double>(), summary["gains"]["margin"].get<double>());
  EXPECT_EQ(row.at("linearised_verdict"), summary["gains"]["sampled_data"]["verdict"]);
  EXPECT_TRUE(row.at("sampled_verdict").is_null()) << "simulated only when the sweep file asks";
  EXPECT_DOUBLE_EQ(row.at("initial_error").get<double>(), 10.0);

  // Another seed draws other directions: other initial states, another table.
  const std::string reseeded = dir + "/reseeded.yaml";
  std::string text = readText(sweep);
  text.replace(text.find("seed: 4"), 7, "seed: 5");
  std::ofstream(reseeded) << text;
  ASSERT_EQ(lagrange("sweep " + quote(reseeded) + " -o " + quote(dir + "/reseeded") + " -q").exit_code, 0);
  EXPECT_NE(tableWithoutWallTime(dir + "/one"), tableWithoutWallTime(dir + "/reseeded"));
}

// simulate_sampled_data: each row's run judged against the same loop at 8 x
// its rate. At 1 kHz the rigid arm's loop is as good as the fine one; at 50 Hz
// it runs away (docs/evidence.md) while the fine loop at 400 Hz converges.
TEST(Sweep, JudgesEachRowAgainstTheFineRateLoopWhenAsked) {
  const std::string dir = freshDir("sweep-sampled");
  fs::create_directories(dir);
  std::ofstream(dir + "/sweep.yaml") << "scenario: " << kConfigs << "/rigid_2dof.yaml\n"
                                     << "set: {duration: 4}\nsimulate_sampled_data: true\n"
                                     << "axes:\n  - {key: plant.publish_rate, values: [1000, 50]}\n";
  const RunResult r = lagrange("sweep " + quote(dir + "/sweep.yaml") + " -o " + quote(dir + "/out") + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream rows(dir + "/out/sweep.jsonl");
  std::string line;
  std::getline(rows, line);
  const auto fast = nlohmann::json::parse(line);
  std::getline(rows, line);
  const auto slow = nlohmann::json::parse(line);
  EXPECT_EQ(fast.at("sampled_verdict"), "adequate") << line;
  EXPECT_EQ(fast.at("fine_rate").get<double>(), 8000.0);
  ASSERT_TRUE(fast.at("converged").get<bool>());
  EXPECT_LE(fast.at("convergence_time").get<double>(),
            1.25 * fast.at("fine_convergence_time").get<double>() + 2e-3);
  EXPECT_FALSE(slow.at("converged").get<bool>()) << line;
  EXPECT_FALSE(slow.at("fine_convergence_time").is_null()) << line;
  EXPECT_EQ(slow.at("sampled_verdict"), "diverges") << line;
  EXPECT_NE(readText(dir + "/out/plan.json").find("\"simulate_sampled_data\":true"), std::string::npos)
      << "the plan keeps the choice, so that shards and Slurm tasks make it too";
}

// A stop while a row is being judged: the fine-rate loops run in the shard
// (on its thread, asking the stop check every 100 ticks); the shard stops
// within moments, and records no row, so a restart runs it.
TEST(Sweep, AStopWhileARowIsJudgedEndsItsSimulationsAtOnce) {
  const std::string dir = freshDir("sweep-stop-judging"), out = dir + "/out";
  fs::create_directories(dir);
  std::ofstream(dir + "/sweep.yaml") << "scenario: " << kConfigs << "/rigid_2dof.yaml\n"
                                     << "set: {duration: 60}\nsimulate_sampled_data: true\n"
                                     << "axes:\n  - {key: plant.publish_rate, values: [1000]}\n"
                                     << "  - {key: plant.physics_step, values: [1.0e-4]}\n";
  Child sweeping({kBin + "/lagrange", "sweep", dir + "/sweep.yaml", "-o", out, "-j", "1"},
                 dir + "/sweep.log");
  // "[s]": the pattern does not match the shell that runs pgrep.
  const std::string shard = "pgrep -f " + quote("[s]weep-shard " + out);
  const auto matches = [&] { return std::stoi("0" + shell(shard + " -c").output); };
  // The shard's CPU time [s]. The row's own run (1 kHz, 0.1 ms physics
  // steps) is about 1 s of it; the judgement's loops at 8 and 16 kHz about
  // 8 s more: a shard past 3 s is judging the row, far from done.
  const auto cpu = [&] {
    const std::string ticks =
        shell("p=$(" + shard + " -o) && awk '{print $14 + $15}' /proc/$p/stat 2>/dev/null").output;
    return std::stod("0" + ticks) / static_cast<double>(sysconf(_SC_CLK_TCK));
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (cpu() < 3.0 && sweeping.running() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_GE(cpu(), 3.0) << "the row was not judged: " << readText(dir + "/sweep.log");
  sweeping.signal(SIGINT);
  EXPECT_EQ(sweeping.wait(10), 130) << "the stop waited for the judgement: " << readText(dir + "/sweep.log");
  EXPECT_TRUE(rowLines(out).empty()) << "a row judged halfway was recorded";
  EXPECT_EQ(matches(), 0) << "the shard outlived the sweep: " << shell(shard).output;
}

TEST(Sweep, ShowsABarWithTheRateAndTheTimeLeftOnATerminal) {
  const std::string dir = freshDir("sweep-tty");
  const std::string sweep = writeSweep(dir, "", 2.0);
  const RunResult r = shell(
      "script -qec " + quote(kBin + "/lagrange sweep " + sweep + " -o " + dir + "/out -j 2") + " /dev/null");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::regex_search(
      r.output, std::regex(R"(\r\[#{30}\] 12/12 runs \(100%\), [0-9.]+ runs/s, ETA 0s, 0 diverged)")))
      << r.output;
  EXPECT_TRUE(std::regex_search(
      r.output, std::regex(R"(\r\[#* *\] [0-9]+/12 runs \( *[0-9]+%\), [0-9.]+ runs/s, ETA [0-9]+s)")))
      << r.output;
  size_t redraws = 0;
  for (size_t at = r.output.find("\r["); at != std::string::npos; at = r.output.find("\r[", at + 1))
    ++redraws;
  EXPECT_GE(redraws, 3u) << "redrawn as rows land";
  EXPECT_EQ(r.output.find("progress:"), std::string::npos) << r.output;
}

TEST(Sweep, AKilledSweepResumesRunningOnlyTheRowsItHadNotFinished) {
  const std::string dir = freshDir("sweep-resume");
  const std::string sweep = writeSweep(dir, "", 3.0);  // 12 runs of about 0.2 s
  const std::string whole = dir + "/whole", out = dir + "/out";
  ASSERT_EQ(lagrange("sweep " + quote(sweep) + " -o " + quote(whole) + " -q").exit_code, 0);

  // SIGKILL the sweep once a few rows are in: nothing is flushed or tidied,
  // and its shards, which would go on writing rows while a restart runs them
  // again, stop with it (PR_SET_PDEATHSIG).
  // "[s]": the pattern does not match the shell that runs pgrep.
  const std::string shards = "pgrep -f " + quote("[s]weep-shard " + out);
  {
    Child sweeping({kBin + "/lagrange", "sweep", sweep, "-o", out, "-j", "2"}, dir + "/first.log");
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while ((!fs::exists(out + "/rows") || rowLines(out).size() < 3) &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_EQ(shell(shards).exit_code, 0) << "the shards run";
    sweeping.signal(SIGKILL);
    sweeping.wait(10);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (shell(shards).exit_code == 0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_NE(shell(shards).exit_code, 0) << "a shard outlived its killed sweep: " << shell(shards).output;
  const std::map<long, int> before = rowLines(out);
  ASSERT_GE(before.size(), 3u);
  ASSERT_LT(before.size(), 12u) << "the sweep ended before it was killed; nothing to resume";
  EXPECT_FALSE(fs::exists(out + "/sweep.csv")) << "a killed sweep writes no table";
  // A row cut off mid-write, as a crash during the write (a shard SIGKILLed
  // too, a node lost) would leave it: dropped.
  long missing = 0;
  while (before.count(missing)) ++missing;
  std::ofstream(out + "/rows/shard-0-of-2.jsonl", std::ios::app)
      << "{\"index\":" << missing << ",\"status\":\"compl";
  const std::string kept = readText(out + "/rows/shard-1-of-2.jsonl");

  const RunResult again = lagrange("sweep " + quote(sweep) + " -o " + quote(out) + " -j 2");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("12 runs of"), std::string::npos) << again.output;
  EXPECT_NE(again.output.find(std::to_string(12 - before.size()) + " to run"), std::string::npos)
      << again.output;
  // Every row once, the finished ones untouched, the table the whole sweep's.
  const std::map<long, int> after = rowLines(out);
  ASSERT_EQ(after.size(), 12u);
  for (const auto& [index, times] : after)
    EXPECT_EQ(times, 1) << "row " << index << " was run " << times << " times";
  EXPECT_EQ(readText(out + "/rows/shard-1-of-2.jsonl").substr(0, kept.size()), kept);
  EXPECT_EQ(tableWithoutWallTime(out), tableWithoutWallTime(whole));

  // Once more: nothing left to run, the same table.
  const RunResult third = lagrange("sweep " + quote(sweep) + " -o " + quote(out));
  ASSERT_EQ(third.exit_code, 0) << third.output;
  EXPECT_NE(third.output.find("0 to run"), std::string::npos) << third.output;
  EXPECT_EQ(rowLines(out), after);
}

TEST(Sweep, BadSweepFilesAreNamedBeforeAnyRunStarts) {
  const std::string dir = freshDir("sweep-bad");
  struct Case {
    std::string axes, expected;
  };
  const std::vector<Case> cases = {
      {"  - {key: controller.gain, values: [1, 2]}\n", "controller.gain"},
      {"  - {key: controller.kd, values: []}\n",
       "axis 'controller.kd' is empty; expected a list of at least one value"},
      {"  - {key: controller.kd, values: [5, -2]}\n", "run 1 (controller.kd=-2)"},
      {"  - {key: plant.publish_rate, range: {from: 0, to: 1000, count: 3, scale: log}}\n",
       "a log scale needs from > 0"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::string path = dir + "/bad" + std::to_string(i) + ".yaml";
    fs::create_directories(dir);
    std::ofstream(path) << "scenario: " << kConfigs << "/rigid_2dof.yaml\naxes:\n" << cases[i].axes;
    const std::string out = dir + "/out" + std::to_string(i);
    const RunResult r = lagrange("sweep " + quote(path) + " -o " + quote(out));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(cases[i].expected), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(path), std::string::npos) << "names the file: " << r.output;
    EXPECT_FALSE(fs::exists(out)) << "nothing was made, let alone run";
  }
  // --dry-run plans and checks, and makes nothing.
  const RunResult dry = lagrange("sweep " + quote(writeSweep(dir + "/dry")) + " --dry-run");
  EXPECT_EQ(dry.exit_code, 0) << dry.output;
  EXPECT_NE(dry.output.find("12 runs of"), std::string::npos) << dry.output;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir + "/dry"), fs::directory_iterator()), 1)
      << "only sweep.yaml";

  // A directory that holds another sweep is not resumed with this one.
  const std::string sweep = writeSweep(dir + "/a", "", 0.2);
  ASSERT_EQ(lagrange("sweep " + quote(sweep) + " -o " + quote(dir + "/out") + " -q").exit_code, 0);
  const std::string other = writeSweep(dir + "/b", "", 0.3);
  const RunResult r = lagrange("sweep " + quote(other) + " -o " + quote(dir + "/out"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("holds another sweep"), std::string::npos) << r.output;
  EXPECT_EQ(lagrange("sweep collect " + quote(dir + "/a")).exit_code, 2) << "not a sweep's directory";

  // Nor is it resumed after its scenario was edited: the rows would mix two scenarios.
  const std::string own = dir + "/c/scenario.yaml";
  fs::create_directories(dir + "/c");
  fs::copy_file(kConfigs + "/rigid_2dof.yaml", own);
  const std::string edited = dir + "/c/sweep.yaml";
  std::ofstream(edited)
      << "scenario: scenario.yaml\nset: {duration: 0.2}\naxes:\n  - {key: controller.kd, values: [5, 20]}\n";
  ASSERT_EQ(lagrange("sweep " + quote(edited) + " -o " + quote(dir + "/c/out") + " -q").exit_code, 0);
  std::ofstream(own, std::ios::app) << "# edited\n";
  const RunResult changed = lagrange("sweep " + quote(edited) + " -o " + quote(dir + "/c/out"));
  EXPECT_EQ(changed.exit_code, 2) << changed.output;
  EXPECT_NE(changed.output.find("holds another sweep"), std::string::npos) << changed.output;
}

// Issue #44: a sweep folder shared on a cluster is writable by others; a
// plan.json planted there after the sweep started (Slurm's array tasks start
// later) names a row whose controller is an external command. Before, the
// shard ran it (the marker was made). Now a shard runs only the plan whose
// SHA-256 its sweep gave it on the command line.
TEST(Sweep, AShardRunsNothingOfAPlanPlantedAfterItsSweepStarted) {
  const std::string dir = freshDir("sweep-planted-plan");
  const std::string sweep = writeSweep(dir, "", 0.05);
  const std::string out = dir + "/out";
  ASSERT_EQ(lagrange("sweep " + quote(sweep) + " -o " + quote(out) + " -q").exit_code, 0);
  std::ifstream in(out + "/plan.json");
  const std::string launched((std::istreambuf_iterator<char>(in)), {});
  const std::array<uint8_t, 32> digest =
      transport::sha256(reinterpret_cast<const uint8_t*>(launched.data()), launched.size());
  const std::string marker = dir + "/MARKER";
  std::string planted =
      std::regex_replace(launched, std::regex(R"("controller\.kd=5")"),
                         "\"controller={type: external, command: [sh, -c, \\\"touch " + marker + "\\\"]}\"");
  ASSERT_NE(planted, launched);
  fs::remove_all(out + "/rows");
  fs::create_directories(out + "/rows");
  std::ofstream(out + "/plan.json", std::ios::trunc) << planted;
  const RunResult shard =
      lagrange("sweep-shard " + quote(out) + " --shard 0 --of 1 --plan-digest " + transport::toHex(digest));
  EXPECT_EQ(shard.exit_code, 2) << shard.output;
  EXPECT_NE(shard.output.find("is not the plan this shard was started for"), std::string::npos)
      << shard.output;
  EXPECT_FALSE(fs::exists(marker)) << "the planted plan's command ran";
  // The plan as launched runs.
  std::ofstream(out + "/plan.json", std::ios::trunc) << launched;
  EXPECT_EQ(
      lagrange("sweep-shard " + quote(out) + " --shard 0 --of 1 --plan-digest " + transport::toHex(digest))
          .exit_code,
      0);
}

// Issue #46: an external row that fails every time was left out of the
// table, and the sweep said "not done yet, run it again" -- which failed the
// same way. Now it is a row with status `failed` and the launcher's reason,
// said on the terminal, and the sweep exits 1; a restart does not run it again.
TEST(Sweep, AnExternalRowThatFailsIsAFailedRowWithItsReason) {
  const std::string dir = freshDir("sweep-external-fails");
  fs::create_directories(dir);
  const std::string sweep = dir + "/sweep.yaml";
  std::ofstream(sweep)
      << "scenario: " << kConfigs << "/rigid_2dof.yaml\n"
      << "set: {duration: 0.2, controller: {type: external, command: [sh, -c, 'sleep 1; exit 5']}}\n"
      << "axes:\n  - {key: plant.physics_step, values: [1.0e-4]}\n";
  const std::string out = dir + "/out";
  const RunResult r = lagrange("sweep " + quote(sweep) + " -o " + quote(out) + " -j 1");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("1 of 1 runs in"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 failed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("row 0 failed: process 'controller' exited with code 5; see "), std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("not done yet"), std::string::npos) << r.output;
  std::ifstream rows(out + "/sweep.jsonl");
  const auto row = nlohmann::json::parse(rows);
  EXPECT_EQ(row["status"], "failed");
  EXPECT_NE(row["stop_reason"].get<std::string>().find("exited with code 5"), std::string::npos)
      << row.dump();
  EXPECT_TRUE(fs::exists(out + "/external/row-0/controller.log")) << "the failed run's logs are kept";
  // Done, not missing: the same command runs nothing again.
  const RunResult again = lagrange("sweep " + quote(sweep) + " -o " + quote(out) + " -j 1");
  EXPECT_EQ(again.exit_code, 1) << again.output;
  EXPECT_EQ(again.output.find("shard"), std::string::npos) << again.output;
}

// A link planted as a shard's log in a shared sweep folder: the shard's
// output was appended to its target (found in review: only the rows files
// were opened without following links). Now refused, the target untouched.
TEST(Sweep, AShardsLogPlantedAsALinkIsRefusedAndItsTargetUntouched) {
  const std::string dir = freshDir("sweep-planted-log");
  const std::string sweep = writeSweep(dir, "", 0.05);
  const std::string out = dir + "/out";
  const std::string victim = dir + "/victim.txt";
  std::ofstream(victim) << "the user's own\n";
  fs::create_directories(out + "/logs");
  fs::create_symlink(victim, out + "/logs/shard-0-of-1.log");
  const RunResult r = lagrange("sweep " + quote(sweep) + " -o " + quote(out) + " -q -j 1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("shard-0-of-1.log' is a symbolic link"), std::string::npos) << r.output;
  std::ifstream in(victim);
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(in)), {}), "the user's own\n");
}

}  // namespace
}  // namespace lagrange::testing
