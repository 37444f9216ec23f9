// The axes a sweep's maps are drawn over (issue #54 item 3: "the automatic
// plots choose the axes that vary; no plot against a constant"). Before, a
// sweep of controller.a: [50] and controller.b: [25, 50, 100] drew
// heat_map.png with every point in one column, and two axes of vector gains
// drew no heat map ("no finished run has numbers in both"). The choice, the
// notes and the data files are tested, not the pixels.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tools/sweep/sweep_maps.hpp"

namespace lagrange::tools::sweep_map_axes_test {

namespace fs = std::filesystem;
using Row = nlohmann::ordered_json;

std::string fileText(const fs::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

bool anyHas(const std::vector<std::string>& lines, const std::string& part) {
  for (const std::string& l : lines)
    if (l.find(part) != std::string::npos) return true;
  return false;
}

class SweepMapAxes : public ::testing::Test {
 protected:
  void SetUp() override {
    out_ = fs::temp_directory_path() / ("lagrange-unit-sweep-map-axes-" + std::to_string(getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(out_);
    fs::create_directories(out_);
    plan_.spec.file = (out_ / "axes_test.yaml").string();
  }
  void TearDown() override { fs::remove_all(out_); }

  // A grid over the axes, in order, each row met when its index is even.
  static std::map<long, Row> grid(const std::vector<std::pair<std::string, std::vector<Row>>>& axes) {
    std::map<long, Row> rows = {{0, Row::object()}};
    for (const auto& [key, values] : axes) {
      std::map<long, Row> next;
      for (const auto& [i, r] : rows)
        for (const Row& v : values) {
          Row n = r;
          n[key] = v;
          next[static_cast<long>(next.size())] = n;
        }
      rows = next;
    }
    for (auto& [i, r] : rows) {
      r["index"] = i;
      r["convergence_time"] = 0.1 * static_cast<double>(i + 1);
      r["verdict"] = i % 2 == 0 ? "met" : "NOT met";
    }
    return rows;
  }
  std::string heatScript(const SweepMapFiles& maps) const {
    for (const std::string& s : maps.scripts)
      if (s.find("set output 'heat_map.png'") != std::string::npos) return s;
    return "";
  }

  fs::path out_;
  SweepPlan plan_;
};

// controller.a: [50], controller.b: [25, 50, 100]: no heat map with every
// point in one column; the convergence map is the line against controller.b.
TEST_F(SweepMapAxes, AnAxisOfOneValueIsNoHeatMapAxisAndTheOtherGetsTheLine) {
  plan_.param_columns = {"controller.a", "controller.b"};
  const auto rows = grid({{"controller.a", {50}}, {"controller.b", {25, 50, 100}}});
  const SweepMapFiles maps = writeSweepMapFiles(out_.string(), plan_, rows);
  EXPECT_TRUE(maps.heat_map_axes.empty());
  EXPECT_EQ(heatScript(maps), "");
  EXPECT_TRUE(anyHas(maps.not_drawn,
                     "heat_map.png: controller.a has one value (50); only controller.b "
                     "varies, and convergence_time.png is drawn against it"))
      << ::testing::PrintToString(maps.not_drawn);
  EXPECT_EQ(maps.convergence_axis, "controller.b");
  ASSERT_FALSE(maps.scripts.empty());
  EXPECT_NE(maps.scripts.front().find("median convergence time at each value"), std::string::npos);
}

// Three axes, the first constant: the heat map is over the two that vary, and says why.
TEST_F(SweepMapAxes, TheDefaultHeatMapIsOverTheFirstTwoAxesThatVary) {
  plan_.param_columns = {"controller.a", "controller.b", "controller.c"};
  const auto rows = grid({{"controller.a", {50}}, {"controller.b", {25, 50}}, {"controller.c", {1, 2, 3}}});
  const SweepMapFiles maps = writeSweepMapFiles(out_.string(), plan_, rows);
  EXPECT_EQ(maps.heat_map_axes, (std::vector<std::string>{"controller.b", "controller.c"}));
  EXPECT_TRUE(anyHas(maps.notes,
                     "heat_map.png: drawn over controller.b and controller.c, the first two axes "
                     "that vary (controller.a has one value (50))"))
      << ::testing::PrintToString(maps.notes);
  // Every axis one value: no heat map, said so.
  const SweepMapFiles one = writeSweepMapFiles(
      out_.string(), plan_, grid({{"controller.a", {50}}, {"controller.b", {25}}, {"controller.c", {1}}}));
  EXPECT_TRUE(one.heat_map_axes.empty());
  EXPECT_TRUE(anyHas(one.not_drawn,
                     "heat_map.png: controller.a has one value (50), controller.b has one value "
                     "(25) and controller.c has one value (1); no axis varies"))
      << ::testing::PrintToString(one.not_drawn);
}

// maps.heat_map names a constant axis: drawn as asked, with a note saying so.
TEST_F(SweepMapAxes, AConstantAxisNamedByMapsHeatMapIsDrawnAsAskedWithANote) {
  plan_.param_columns = {"controller.a", "controller.b"};
  plan_.spec.heat_map = {"controller.a", "controller.b"};
  const auto rows = grid({{"controller.a", {50}}, {"controller.b", {25, 50, 100}}});
  const SweepMapFiles maps = writeSweepMapFiles(out_.string(), plan_, rows);
  EXPECT_EQ(maps.heat_map_axes, plan_.spec.heat_map);
  EXPECT_TRUE(anyHas(maps.notes,
                     "heat_map.png: controller.a has one value (50), yet maps.heat_map names it: "
                     "every point is in one column"))
      << ::testing::PrintToString(maps.notes);
  EXPECT_FALSE(anyHas(maps.not_drawn, "heat_map.png"));
}

// Two axes of 2-joint vector gains: a heat map over the vectors, each a
// tick named as written; the CSV holds each place and its value.
TEST_F(SweepMapAxes, VectorAxesDrawACategoricalHeatMapWithNamedTicks) {
  plan_.param_columns = {"controller.kd", "controller.kp"};
  const auto rows =
      grid({{"controller.kd", {Row::parse("[5, 0.4]"), Row::parse("[15, 1]"), Row::parse("[30, 2]")}},
            {"controller.kp", {Row::parse("[100, 8]"), Row::parse("[150, 10]")}}});
  const SweepMapFiles maps = writeSweepMapFiles(out_.string(), plan_, rows);
  EXPECT_EQ(maps.heat_map_axes, (std::vector<std::string>{"controller.kd", "controller.kp"}));
  EXPECT_FALSE(anyHas(maps.not_drawn, "heat_map.png")) << ::testing::PrintToString(maps.not_drawn);
  const std::string script = heatScript(maps);
  EXPECT_NE(script.find("set xtics ('[5, 0.4]' 0, '[15, 1]' 1, '[30, 2]' 2)"), std::string::npos) << script;
  EXPECT_NE(script.find("set ytics ('[100, 8]' 0, '[150, 10]' 1)"), std::string::npos) << script;
  EXPECT_EQ(script.find("logscale"), std::string::npos) << script;
  // Rows in grid order, kp fastest: even indices met, so kp [100, 8] always met.
  EXPECT_EQ(fileText(out_ / "maps" / "heat_map.csv"),
            "controller.kd,controller.kp,met_fraction,runs,met,not_met,not_judged,"
            "\"controller.kd value\",\"controller.kp value\"\n"
            "0,0,1,1,1,0,0,\"[5, 0.4]\",\"[100, 8]\"\n"
            "0,1,0,1,0,1,0,\"[5, 0.4]\",\"[150, 10]\"\n"
            "1,0,1,1,1,0,0,\"[15, 1]\",\"[100, 8]\"\n"
            "1,1,0,1,0,1,0,\"[15, 1]\",\"[150, 10]\"\n"
            "2,0,1,1,1,0,0,\"[30, 2]\",\"[100, 8]\"\n"
            "2,1,0,1,0,1,0,\"[30, 2]\",\"[150, 10]\"\n");
}

// A vector axis against a scalar one: the scalar at its numbers (a log axis
// over a decade), the vector by its named places.
TEST_F(SweepMapAxes, AVectorAxisAgainstAScalarOneKeepsTheScalarsNumbers) {
  plan_.param_columns = {"controller.kd", "plant.publish_rate"};
  const auto rows = grid({{"controller.kd", {Row::parse("[5, 0.4]"), Row::parse("[15, 1]")}},
                          {"plant.publish_rate", {100, 1000}}});
  const SweepMapFiles maps = writeSweepMapFiles(out_.string(), plan_, rows);
  EXPECT_EQ(maps.heat_map_axes, (std::vector<std::string>{"controller.kd", "plant.publish_rate"}));
  const std::string script = heatScript(maps);
  EXPECT_NE(script.find("set xtics ('[5, 0.4]' 0, '[15, 1]' 1)"), std::string::npos) << script;
  EXPECT_NE(script.find("set logscale y"), std::string::npos) << script;
  EXPECT_EQ(script.find("set ytics"), std::string::npos) << script;
  EXPECT_EQ(fileText(out_ / "maps" / "heat_map.csv"),
            "controller.kd,plant.publish_rate,met_fraction,runs,met,not_met,not_judged,"
            "\"controller.kd value\"\n"
            "0,100,1,1,1,0,0,\"[5, 0.4]\"\n0,1000,0,1,0,1,0,\"[5, 0.4]\"\n"
            "1,100,1,1,1,0,0,\"[15, 1]\"\n1,1000,0,1,0,1,0,\"[15, 1]\"\n");
}

}  // namespace lagrange::tools::sweep_map_axes_test
