// The two physics engines side by side (plant.engine, plant/physics_engine.hpp):
// a MuJoCo run is as deterministic as an ODE one -- lockstep equals in-process
// bit for bit, and its log replays through the plant -- and every shipped
// config runs on both, to the same verdict at the same time or to a
// difference that is the engine's, explained.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"
#include "support/wait.hpp"

namespace lagrange::testing {
namespace {

// Joint damping and friction too: MuJoCo's constraint solver starts each step
// from the last one's answer, which a replay must rebuild in the same order.
constexpr const char* kMujocoPelican =
    "-q --set duration=2 --set plant.engine=mujoco --set plant.physics_step=1e-3 "
    "--set 'plant.joint_damping=[0.3, 0.05]' --set 'plant.joint_friction=[0.2, 0.05]'";

TEST(Engines, AMujocoRunIsTheSameInLockstepAndInProcessAndItsLogReplaysThroughThePlant) {
  const std::string config = kConfigs + "/rigid_2dof.yaml";
  const std::string lockstep = freshDir("mujoco-lockstep"), inproc = freshDir("mujoco-inproc");
  const RunResult a = runScenario(config, lockstep, std::string(kMujocoPelican) + " --mode lockstep");
  const RunResult b = runScenario(config, inproc, std::string(kMujocoPelican) + " --mode inproc");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const auto ta = readTruth(lockstep + "/run.lcm"), tb = readTruth(inproc + "/run.lcm");
  ASSERT_EQ(ta.size(), 2001u);
  ASSERT_EQ(tb.size(), 2001u);
  for (size_t k = 0; k < ta.size(); ++k) {
    ASSERT_EQ(ta[k].q, tb[k].q) << "tick " << k;
    ASSERT_EQ(ta[k].energy, tb[k].energy) << "tick " << k;
  }
  EXPECT_EQ(readCommands(lockstep + "/run.lcm"), readCommands(inproc + "/run.lcm"));
  // The run says which engine it ran on, where a user reads it back.
  const auto j = readSummary(lockstep);
  EXPECT_EQ(j["plant"]["engine"], "mujoco") << j["plant"].dump();
  EXPECT_EQ(j["plant"]["mujoco_integrator"], "rk4") << j["plant"].dump();
  EXPECT_NE(slurp(lockstep + "/config.resolved.yaml").find("engine: mujoco"), std::string::npos);
  // Replay rebuilds the engine the log's scenario names: the plant's
  // answers, every tick, bit for bit (on ODE they would differ at once).
  const RunResult replay = lagrange("replay " + quote(lockstep + "/run.lcm") + " --component plant");
  EXPECT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_NE(replay.output.find("plant reproduced all 2001"), std::string::npos) << replay.output;
}

// plant.engine is an axis like any key: a sweep over both engines, each
// row naming its engine, both converging at the same time; and a key of
// compare's sweep (docs/evidence.md, "Does the verdict depend on the engine?").
TEST(Engines, AreAnAxisOfASweep) {
  const std::string dir = freshDir("engine-sweep");
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/sweep.yaml") << "scenario: " << kConfigs << "/rigid_2dof.yaml\nset: {duration: 2}\n"
                                     << "axes:\n  - {key: plant.engine, values: [ode, mujoco]}\n";
  const RunResult r = lagrange("sweep " + quote(dir + "/sweep.yaml") + " -o " + quote(dir + "/out") + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream rows(dir + "/out/sweep.jsonl");
  std::string line;
  std::map<std::string, double> converged_at;
  while (std::getline(rows, line)) {
    const auto row = nlohmann::json::parse(line);
    ASSERT_TRUE(row.at("converged").get<bool>()) << line;
    converged_at[row.at("plant.engine").get<std::string>()] = row.at("convergence_time").get<double>();
  }
  ASSERT_EQ(converged_at.size(), 2u);
  EXPECT_NEAR(converged_at["mujoco"], converged_at["ode"], 0.01 * converged_at["ode"]);

  // compare's sweep: one row per engine, each run on the engine its row names.
  const std::string cmp = dir + "/compare";
  const RunResult c =
      lagrange("compare " + quote(kConfigs + "/compare_pelican.yaml") + " -o " + quote(cmp) +
               " -q --set duration=2 --controllers theorem1 --sweep 'plant.engine=[ode, mujoco]'");
  ASSERT_EQ(c.exit_code, 0) << c.output;
  const std::string table = slurp(cmp + "/comparison.csv");
  for (const std::string engine : {"ode", "mujoco"})
    EXPECT_NE(table.find("theorem1,plant.engine,\"" + engine + "\",completed,"), std::string::npos) << table;
  int mujoco_runs = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(cmp + "/runs/theorem1"))
    if (entry.path().filename() == "summary.json") {
      const auto summary = readSummary(entry.path().parent_path().string());
      const bool on_mujoco = summary.contains("plant") && summary["plant"]["engine"] == "mujoco";
      EXPECT_EQ(on_mujoco, entry.path().string().find("mujoco") != std::string::npos) << entry.path();
      mujoco_runs += on_mujoco;
    }
  EXPECT_EQ(mujoco_runs, 1);
}

class EngineAgreement : public ::testing::TestWithParam<std::string> {};

// Every shipped config on both engines, at its own physics step (ODE at 0.1 ms
// for the configs that ship on MuJoCo): the verdict
// does not depend on the engine -- both meet the metric and converge within
// 1 % of each other's time (measured: within 0.1 %) -- except where the
// difference is the engine's, explained and asserted:
//  - flexible_2dof_filtered_rate: its sampled loop is unstable (check-gains:
//    |mu| = 1.0017, the config says so) and converges on ODE only because
//    ODE's first-order stepper damps the slowly growing mode; MuJoCo, which
//    follows the model to 1e-6 rad where ODE is 1e-3 off, lets it grow until
//    the plant stops the run. The engine was the verdict's.
//  - rigid_2dof_large_error: from 2 000 rad/s of spin the transient is so
//    sensitive that the convergence time moves by 10 % with the step on
//    either engine (ODE 1.235, 1.097, 1.112 s at 100, 25, 10 us; MuJoCo
//    1.03, 1.061 s at 100, 25 us): both converge, within 25 %.
TEST_P(EngineAgreement, EveryShippedConfigRunsOnBothEnginesToTheSameVerdict) {
  const std::string name = GetParam();
  const std::string config = kConfigs + "/" + name + ".yaml";
  const std::string ode = freshDir("engine-ode"), mujoco = freshDir("engine-mujoco");
  // A config shipped on MuJoCo at 1 ms (the URDF arms) runs on ODE at 0.1 ms,
  // the step it had on ODE (docs/engines_and_arms.md, "Two engines").
  const bool ships_on_mujoco = slurp(config).find("\n  engine: mujoco") != std::string::npos;
  const RunResult a = runScenario(config, ode,
                                  std::string("-q --mode inproc --set plant.engine=ode") +
                                      (ships_on_mujoco ? " --set plant.physics_step=1e-4" : ""));
  const RunResult b = runScenario(config, mujoco, "-q --mode inproc --set plant.engine=mujoco");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  const auto ja = readSummary(ode)["tracking"];
  EXPECT_TRUE(ja["met"].get<bool>()) << ja.dump();
  if (name == "flexible_2dof_filtered_rate") {
    EXPECT_EQ(b.exit_code, 1) << b.output;
    EXPECT_NE(b.output.find("which MuJoCo cannot integrate; the closed loop is unstable"), std::string::npos)
        << b.output;
    EXPECT_EQ(readSummary(mujoco)["status"], "diverged");
    return;
  }
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const auto jb = readSummary(mujoco)["tracking"];
  EXPECT_TRUE(jb["met"].get<bool>()) << jb.dump();
  const double ta = ja["convergence_time"].get<double>(), tb = jb["convergence_time"].get<double>();
  RecordProperty("convergence_ode", std::to_string(ta));
  RecordProperty("convergence_mujoco", std::to_string(tb));
  const double within = name == "rigid_2dof_large_error" ? 0.25 : 0.01;
  EXPECT_NEAR(tb, ta, within * ta) << "ODE " << ta << " s, MuJoCo " << tb << " s";
}

INSTANTIATE_TEST_SUITE_P(Configs, EngineAgreement, ::testing::ValuesIn(shippedConfigs()),
                         [](const ::testing::TestParamInfo<std::string>& config_name) {
                           return config_name.param;
                         });

}  // namespace
}  // namespace lagrange::testing
