// A sweep's maps draw each row by its verdict (issue #52): the `verdict` and
// `verdict_kind` columns the run's verdict wrote (logger/verdict.hpp), never
// `converged` or `diverged` decided again. Before, a run that converged but
// missed its metric (late, or a realtime loop off its rate) was drawn as
// converged, and a diverged one by the maps' own rule. And the convergence
// map is drawn against the swept axis, numbers or not, never against a
// constant ||x(0)|| (issue #54 item 3); a one-axis sweep draws a line.
// The classes and the data files are tested, not the pixels.
#include "tools/sweep/sweep_maps.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace lagrange::tools::sweep_maps_test {

namespace fs = std::filesystem;
using Row = nlohmann::ordered_json;

std::string fileText(const fs::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(SweepMaps, APointsClassIsItsRowsVerdictNotItsConvergence) {
  // Converged in 0.5 s, but the realtime loop was off its rate: NOT met, timing.
  const VerdictClass timing = verdictClass(Row::parse(
      R"({"status":"completed","diverged":false,"converged":true,"convergence_time":0.5,)"
      R"("verdict":"NOT met","verdict_reason":"the plant loop was on time on 80 % of its periods",)"
      R"("verdict_kind":"timing"})"));
  EXPECT_EQ(timing.key, "not_met_timing");
  EXPECT_EQ(timing.label, "NOT met: timing");
  EXPECT_FALSE(timing.met);
  const VerdictClass unstable = verdictClass(
      Row::parse(R"({"converged":false,"verdict":"NOT met","verdict_kind":"unstable_at_rate"})"));
  EXPECT_EQ(unstable.label, "NOT met: unstable at rate");
  // The verdict decides, whatever the other columns say.
  EXPECT_TRUE(verdictClass(Row::parse(R"({"converged":false,"diverged":true,"verdict":"met"})")).met);
  EXPECT_EQ(verdictClass(Row::parse(R"({"converged":true,"verdict":"not judged"})")).key, "not_judged");
  EXPECT_EQ(verdictClass(Row::parse(R"({"verdict":"NOT met","verdict_kind":null})")).label, "NOT met");
  EXPECT_EQ(verdictClass(Row::parse(R"({"status":"failed","verdict":null})")).key, "failed");
  // A row of a sweep from before verdicts: said so, not judged by the maps.
  EXPECT_EQ(verdictClass(Row::parse(R"({"status":"diverged","diverged":true})")).key, "no_verdict");
  // A kind is a file name's word: nothing else gets into it.
  EXPECT_EQ(verdictClass(Row::parse(R"({"verdict":"NOT met","verdict_kind":"../x y"})")).key,
            "not_met____x_y");
}

class SweepMapsFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    out_ = fs::temp_directory_path() / ("lagrange-unit-sweep-maps-" + std::to_string(getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(out_);
    fs::create_directories(out_);
    plan_.spec.file = (out_ / "maps_test.yaml").string();
  }
  void TearDown() override { fs::remove_all(out_); }
  fs::path out_;
  SweepPlan plan_;
};

// One axis, x0_norm the same in every row: the map is drawn against the axis,
// each point in its verdict's class, with a line through the median times.
TEST_F(SweepMapsFiles, TheConvergenceMapDrawsEachRowInItsVerdictsClassAgainstTheSweptAxis) {
  plan_.param_columns = {"plant.publish_rate"};
  const std::map<long, Row> rows = {
      {0, Row::parse(R"({"index":0,"plant.publish_rate":1000,"x0_norm":2.5,"converged":true,)"
                     R"("convergence_time":0.4,"verdict":"met"})")},
      {1, Row::parse(R"({"index":1,"plant.publish_rate":250,"x0_norm":2.5,"converged":true,)"
                     R"("convergence_time":0.5,"verdict":"NOT met","verdict_kind":"timing"})")},
      {2, Row::parse(R"({"index":2,"plant.publish_rate":40,"x0_norm":2.5,"converged":false,"diverged":true,)"
                     R"("convergence_time":null,"verdict":"NOT met","verdict_kind":"diverged"})")}};
  const SweepMapFiles maps = writeSweepMapFiles(out_.string(), plan_, rows);
  EXPECT_EQ(maps.convergence_axis, "plant.publish_rate");
  EXPECT_EQ(maps.convergence_classes,
            (std::vector<std::string>{"met", "NOT met: diverged", "NOT met: timing"}));
  const fs::path dir = out_ / "maps";
  // The timing row is drawn at its convergence time in its own class, not as converged.
  EXPECT_EQ(fileText(dir / "convergence_not_met_timing.csv"), "x,y,group\n250,0.5,1\n");
  EXPECT_EQ(fileText(dir / "convergence_met.csv"), "x,y,group\n1000,0.4,1\n");
  EXPECT_NE(fileText(dir / "convergence_not_met_diverged.csv").find("\n40,"), std::string::npos);
  ASSERT_FALSE(maps.scripts.empty());
  const std::string& script = maps.scripts.front();
  EXPECT_NE(script.find("title 'NOT met: timing'"), std::string::npos) << script;
  EXPECT_EQ(script.find("not converged"), std::string::npos) << script;
  EXPECT_NE(script.find("set xlabel 'plant.publish_rate'"), std::string::npos) << script;
  EXPECT_NE(script.find("median convergence time at each value"), std::string::npos) << script;
  EXPECT_EQ(fileText(dir / "convergence_median.csv"), "x,median_convergence_time\n250,0.5\n1000,0.4\n");
}

// Values that are not numbers (vectors): drawn in order, each named, not
// against ||x(0)||; and the heat map's fraction is of runs whose verdict is met.
TEST_F(SweepMapsFiles, AnAxisOfVectorsIsDrawnInOrderAndTheHeatMapCountsMetVerdicts) {
  plan_.param_columns = {"controller.a", "controller.kd"};
  std::map<long, Row> rows;
  long i = 0;
  for (const char* a : {"[20, 30]", "[50, 50]", "[100, 10]"})
    for (const int kd : {5, 20}) {
      Row r;
      r["index"] = i;
      r["controller.a"] = a;
      r["controller.kd"] = kd;
      r["x0_norm"] = 3.0;
      r["converged"] = true;
      r["convergence_time"] = 0.3 + 0.1 * static_cast<double>(i);
      r["verdict"] = kd == 5 ? "met" : "NOT met";  // kd 20: converged, but late
      r["verdict_kind"] = kd == 5 ? Row() : Row("late");
      rows[i++] = r;
    }
  const SweepMapFiles maps = writeSweepMapFiles(out_.string(), plan_, rows);
  EXPECT_EQ(maps.convergence_axis, "controller.a");
  EXPECT_EQ(maps.convergence_classes, (std::vector<std::string>{"met", "NOT met: late"}));
  const std::string& script = maps.scripts.front();
  EXPECT_NE(script.find("set xtics ('[20, 30]' 0, '[50, 50]' 1, '[100, 10]' 2)"), std::string::npos)
      << script;
  EXPECT_NE(script.find("controller.kd = 20"), std::string::npos) << script;  // coloured by the other axis
  EXPECT_EQ(fileText(out_ / "maps" / "convergence_not_met_late.csv"),
            "x,y,group\n0,0.4,2\n1,0.6,2\n2,0.8,2\n");
  // The heat map is drawn over the vectors too, each a named tick (sweep_map_axes_test.cpp).
  EXPECT_EQ(maps.heat_map_axes, (std::vector<std::string>{"controller.a", "controller.kd"}));

  // x0_norm is one value: a heat map over it only when the file asks (and then with a note).
  plan_.param_columns = {"controller.kd", "x0_norm"};
  plan_.spec.heat_map = plan_.param_columns;
  const SweepMapFiles heat = writeSweepMapFiles(out_.string(), plan_, rows);
  ASSERT_EQ(heat.notes.size(), 1u);
  EXPECT_NE(heat.notes[0].find("x0_norm has one value (3)"), std::string::npos) << heat.notes[0];
  EXPECT_EQ(
      fileText(out_ / "maps" / "heat_map.csv"),
      "controller.kd,x0_norm,met_fraction,runs,met,not_met,not_judged\n5,3,1,3,3,0,0\n20,3,0,3,0,3,0\n");
}

}  // namespace lagrange::tools::sweep_maps_test
