// lagrange sweep's plan and rows files (tools/sweep/sweep_plan.hpp,
// tools/sweep/sweep_store.hpp): what each row runs is fixed by the sweep file and
// its seed; bad sweep files are named with what was expected; a partial line
// a killed shard left is dropped and cut.
#include "tools/sweep/sweep_plan.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "model/reference.hpp"
#include "support/configs.hpp"
#include "tools/sweep/sweep_random.hpp"
#include "tools/sweep/sweep_store.hpp"

namespace lagrange::tools {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& tag) {
  const fs::path dir =
      fs::temp_directory_path() / ("lagrange-unit-sweep-" + tag + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string writeSweep(const fs::path& dir, const std::string& body) {
  const fs::path p = dir / "sweep.yaml";
  std::ofstream(p) << "scenario: " << testing::kConfigs << "/rigid_2dof.yaml\n" << body;
  return p.string();
}

std::string errorOf(const std::string& path) {
  try {
    planSweep(readSweepSpec(path));
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SweepPlan, AGridRunsEveryCombinationLastAxisFastestWithExactEnds) {
  const fs::path dir = scratch("grid");
  const SweepPlan plan = planSweep(readSweepSpec(
      writeSweep(dir,
                 "axes:\n"
                 "  - {key: controller.kd, values: [5, 20]}\n"
                 "  - {key: plant.publish_rate, range: {from: 100, to: 10000, count: 3, scale: log}}\n")));
  ASSERT_EQ(plan.rows.size(), 6u);
  EXPECT_EQ(plan.param_columns, (std::vector<std::string>{"controller.kd", "plant.publish_rate"}));
  const std::vector<std::vector<std::string>> expected = {{"5", "100"},  {"5", "1000"},  {"5", "10000"},
                                                          {"20", "100"}, {"20", "1000"}, {"20", "10000"}};
  for (size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(plan.rows[i].index, static_cast<long>(i));
    EXPECT_EQ(plan.rows[i].params, expected[i]);
    EXPECT_EQ(plan.rows[i].overrides.back(), "plant.publish_rate=" + expected[i][1]);
  }
}

TEST(SweepPlan, ANormAxisSetsTheInitialErrorAboutTheReferenceInTheSameDirectionsAcrossOtherAxes) {
  const fs::path dir = scratch("norm");
  const SweepPlan plan = planSweep(readSweepSpec(
      writeSweep(dir,
                 "seed: 3\naxes:\n"
                 "  - {key: controller.kd, values: [5, 20]}\n"
                 "  - {key: initial_state.q, norm: {from: 0.01, to: 1000, count: 3, scale: log}, "
                 "directions: 2}\n")));
  ASSERT_EQ(plan.rows.size(), 12u);
  std::set<std::vector<double>> directions;
  for (const SweepRow& row : plan.rows) {
    const config::Scenario s = config::loadScenario(plan.spec.scenario_path, row.overrides);
    const Eigen::VectorXd e = s.initial_state.q - model::Reference(s.reference).evaluate(0.0, 1).q();
    const double r = std::stod(row.params[1]);
    EXPECT_NEAR(e.norm(), r, 1e-12 * std::max(1.0, r)) << row.index;
    const Eigen::VectorXd u = e / e.norm();
    directions.insert({std::round(u[0] * 1e9), std::round(u[1] * 1e9)});
  }
  EXPECT_EQ(std::stod(plan.rows[0].params[1]), 0.01);
  EXPECT_EQ(std::stod(plan.rows[5].params[1]), 1000.0);
  EXPECT_EQ(directions.size(), 2u) << "every kd and norm reuses the axis's two directions";
}

TEST(SweepPlan, RandomAndHaltonDesignsAreTheSameForASeedAndStayInTheirBounds) {
  const fs::path dir = scratch("random");
  for (const std::string design : {"random", "halton"}) {
    const std::string body = "design: " + design +
                             "\nsamples: 40\nseed: SEED\naxes:\n"
                             "  - {key: controller.kd, range: {from: 1, to: 100, scale: log}}\n"
                             "  - {key: controller.a, range: {from: 10, to: 20}}\n";
    const auto plan = [&](int seed) {
      std::string b = body;
      b.replace(b.find("SEED"), 4, std::to_string(seed));
      return planSweep(readSweepSpec(writeSweep(dir, b)));
    };
    const SweepPlan a = plan(1), again = plan(1), other = plan(2);
    ASSERT_EQ(a.rows.size(), 40u);
    std::set<std::string> kds;
    for (size_t i = 0; i < a.rows.size(); ++i) {
      EXPECT_EQ(a.rows[i].overrides, again.rows[i].overrides) << design;
      const double kd = std::stod(a.rows[i].params[0]), ad = std::stod(a.rows[i].params[1]);
      EXPECT_GE(kd, 1.0);
      EXPECT_LE(kd, 100.0);
      EXPECT_GE(ad, 10.0);
      EXPECT_LE(ad, 20.0);
      kds.insert(a.rows[i].params[0]);
    }
    EXPECT_EQ(kds.size(), 40u) << design << ": every sample its own value";
    EXPECT_NE(a.rows[0].params, other.rows[0].params) << design << ": another seed, other samples";
  }
}

TEST(SweepPlan, HaltonPointsFillTheUnitSquareMoreEvenlyThanRandomDraws) {
  // 64 points in an 8 x 8 grid of cells: independent uniform draws leave
  // about 23 cells empty (64 (63/64)^64), a low-discrepancy set far fewer.
  for (std::uint64_t seed : {1, 5, 9}) {
    const HaltonSequence h(2, seed);
    std::set<std::pair<int, int>> halton, random;
    for (long i = 0; i < 64; ++i) {
      const double x = h.at(i, 0), y = h.at(i, 1);
      ASSERT_GE(x, 0.0);
      ASSERT_LT(x, 1.0);
      halton.insert({static_cast<int>(x * 8), static_cast<int>(y * 8)});
      random.insert(
          {static_cast<int>(uniform01(seed, 1, i) * 8), static_cast<int>(uniform01(seed, 2, i) * 8)});
    }
    EXPECT_GE(halton.size(), 48u) << seed;
    EXPECT_GT(halton.size(), random.size() + 4) << seed;
  }
}

TEST(SweepPlan, DirectionsAreUnitVectorsSpreadOverTheSphere) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::uint64_t i = 0; i < 4000; ++i) {
    const Eigen::VectorXd u = unitDirection(11, kStreamDirection, i, 3);
    ASSERT_NEAR(u.norm(), 1.0, 1e-12);
    mean += u;
  }
  EXPECT_LT((mean / 4000).norm(), 0.05) << "no preferred direction";
  EXPECT_EQ(unitDirection(11, kStreamDirection, 7, 3), unitDirection(11, kStreamDirection, 7, 3));
}

TEST(SweepPlan, BadSweepFilesAreNamedWithWhatWasExpected) {
  const fs::path dir = scratch("bad");
  {
    const std::string e = errorOf(writeSweep(dir, "axes:\n  - {key: controller.kd, values: []}\n"));
    EXPECT_NE(e.find("axis 'controller.kd' is empty"), std::string::npos) << e;
  }
  {
    const std::string e = errorOf(writeSweep(dir, "axes:\n  - {key: controller.kdd, values: [1]}\n"));
    EXPECT_NE(e.find("controller.kdd"), std::string::npos) << e;
    EXPECT_NE(e.find("run 0"), std::string::npos) << e;
  }
  {
    const std::string e = errorOf(writeSweep(dir, "axes:\n  - {key: controller.kd, values: [5, -1]}\n"));
    EXPECT_NE(e.find("run 1 (controller.kd=-1)"), std::string::npos) << e;
  }
  {
    const std::string e = errorOf(writeSweep(dir, "axis:\n  - {key: controller.kd, values: [5]}\n"));
    EXPECT_NE(e.find("axis: unknown key"), std::string::npos) << e;
  }
  {
    const std::string e = errorOf(
        writeSweep(dir, "axes:\n  - {key: controller.kd, range: {from: 0, to: 1, scale: log, count: 2}}\n"));
    EXPECT_NE(e.find("log scale needs from > 0"), std::string::npos) << e;
  }
  {
    const std::string e =
        errorOf(writeSweep(dir, "design: random\naxes:\n  - {key: controller.kd, values: [5]}\n"));
    EXPECT_NE(e.find("samples"), std::string::npos) << e;
  }
}

TEST(SweepStore, APartialLineAKilledShardLeftIsDroppedAndCutBeforeTheNextRow) {
  const fs::path dir = scratch("store");
  fs::create_directories(dir / "rows");
  const fs::path file = dir / "rows" / "shard-0-of-1.jsonl";
  std::ofstream(file) << "{\"index\":0,\"status\":\"completed\"}\n{\"index\":1,\"sta";
  auto rows = readFinishedRows(dir.string(), 2).rows;
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows.begin()->first, 0);
  {
    RowWriter writer(file.string());
    nlohmann::ordered_json row;
    row["index"] = 1;
    row["status"] = "completed";
    writer.append(row);
  }
  rows = readFinishedRows(dir.string(), 2).rows;
  ASSERT_EQ(rows.size(), 2u);
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "{\"index\":0,\"status\":\"completed\"}\n{\"index\":1,\"status\":\"completed\"}\n");
}

// A row written before the simulated verdict existed called the linearised
// verdict sampled_verdict: read back, it is linearised_verdict, and the
// simulated column is empty.
TEST(SweepStore, AnOldRowsSampledVerdictIsReadAsTheLinearisedOne) {
  const fs::path dir = scratch("store-old");
  fs::create_directories(dir / "rows");
  std::ofstream(dir / "rows" / "shard-0-of-1.jsonl")
      << "{\"index\":0,\"sampled_verdict\":\"slow\",\"spectral_radius\":0.99}\n"
         "{\"index\":1,\"linearised_verdict\":\"adequate\",\"sampled_verdict\":\"diverges\"}\n";
  const auto rows = readFinishedRows(dir.string(), 2).rows;
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows.at(0).at("linearised_verdict"), "slow");
  EXPECT_TRUE(rows.at(0).at("sampled_verdict").is_null());
  EXPECT_EQ(rows.at(1).at("linearised_verdict"), "adequate");
  EXPECT_EQ(rows.at(1).at("sampled_verdict"), "diverges");
}

// A plan.json of before 2026-11-27 wrote 17 significant digits; the same
// plan written now, with shortest numbers, is the same plan (a resume of
// that sweep is accepted), and one number changed is another plan.
TEST(SweepPlan, APlanWrittenWithSeventeenDigitsIsTheSamePlan) {
  const std::string now =
      "{\"sweep_file\":\"run2/s.yaml\",\"rows\":1}\n"
      "{\"index\":0,\"params\":[\"0.1\",\"1e-05\"],\"overrides\":[\"initial_state.q=[0.1, -0.3]\"]}\n";
  const std::string before =
      "{\"sweep_file\":\"run2/s.yaml\",\"rows\":1}\n"
      "{\"index\":0,\"params\":[\"0.10000000000000001\",\"1.0000000000000001e-05\"],"
      "\"overrides\":[\"initial_state.q=[0.10000000000000001, -0.29999999999999999]\"]}\n";
  ASSERT_NE(now, before);
  EXPECT_TRUE(samePlanText(now, before));
  std::string other = before;
  other.replace(other.find("-0.29999999999999999"), 20, "-0.29999999999999993");
  EXPECT_FALSE(samePlanText(now, other));
  EXPECT_FALSE(samePlanText(now, "{\"sweep_file\":\"run3/s.yaml\",\"rows\":1}\n"));
  // Whole numbers are compared as written: two seeds above 2^53 one apart
  // are the same double, not the same plan.
  EXPECT_FALSE(samePlanText("{\"seed\":9007199254740993}", "{\"seed\":9007199254740992}"));
}
}  // namespace
}  // namespace lagrange::tools
