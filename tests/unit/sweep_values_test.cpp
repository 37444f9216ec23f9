// A sweep's rows hold each axis value typed as the scenario reads it (issue
// #54 item 3): a vector gain is a list of numbers, not its YAML text
// "[5.0, 0.4]"; a number a number, `true` a bool, a reference type a string.
// Rows written before, with the text, are read back typed; sweep.csv has a
// column per element of a vector axis. The row writer (SweepRunner's
// failedRow, which writes the same parameter columns as a run's row), the
// reader (readFinishedRows), the table (writeSweepTable) and the maps'
// labels are tested; no run is made.
#include "tools/sweep/sweep_values.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tools/sweep/sweep_maps.hpp"
#include "tools/sweep/sweep_runner.hpp"
#include "tools/sweep/sweep_store.hpp"

namespace lagrange::tools::sweep_values_test {

namespace fs = std::filesystem;
using Row = nlohmann::ordered_json;
using Json = nlohmann::ordered_json;  // what typedParam gives: a map in the order written

std::string fileText(const fs::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

class SweepValues : public ::testing::Test {
 protected:
  void SetUp() override {
    out_ = fs::temp_directory_path() / ("lagrange-unit-sweep-values-" + std::to_string(getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(out_);
    fs::create_directories(out_ / "rows");
    plan_.spec.file = (out_ / "sweep.yaml").string();
    plan_.param_columns = {"controller.kd", "reference.type", "plant.publish_rate", "faults.enabled"};
  }
  void TearDown() override { fs::remove_all(out_); }
  fs::path out_;
  SweepPlan plan_;
};

TEST(SweepValue, EachAxisTextIsTheValueTheScenarioReads) {
  const Json kd = typedParam("[5.0, 0.4]");
  ASSERT_TRUE(kd.is_array());
  EXPECT_EQ(kd.size(), 2u);
  EXPECT_TRUE(kd[0].is_number_float() && kd[1].is_number_float());
  EXPECT_EQ(kd, Json::parse("[5.0, 0.4]"));
  EXPECT_EQ(typedParam("[150, 10]").dump(), "[150.0,10.0]");  // numbers as the rows always had them
  EXPECT_EQ(typedParam("1000"), Json(1000.0));
  EXPECT_TRUE(typedParam("1000").is_number_float());
  EXPECT_EQ(typedParam("1e-3"), Json(1e-3));
  EXPECT_EQ(typedParam("sine"), Json("sine"));
  EXPECT_EQ(typedParam("true"), Json(true));
  EXPECT_EQ(typedParam("false"), Json(false));
  EXPECT_TRUE(typedParam("~").is_null());
  // A quoted scalar is the string it holds (YAML's flow text of "a, b").
  EXPECT_EQ(typedParam("\"a, b\""), Json("a, b"));
  EXPECT_EQ(typedParam("'true'"), Json("true"));
  EXPECT_EQ(typedParam("{type: sine, amplitude: [1, 0.5]}").dump(),
            R"({"type":"sine","amplitude":[1.0,0.5]})");
  // Not YAML: the text as it is; infinite: not a JSON number, the text.
  EXPECT_EQ(typedParam("[1, 2"), Json("[1, 2"));
  EXPECT_EQ(typedParam("inf"), Json("inf"));
  // Nested past the bound a row is read back with: the text.
  const std::string deep = std::string(20, '[') + "1" + std::string(20, ']');
  EXPECT_EQ(typedParam(deep), Json(deep));
}

// What a row's writer puts in the parameter columns: typed values.
TEST_F(SweepValues, ARowHoldsEachAxisValueTyped) {
  const SweepRunner runner(plan_);
  const Row row = runner.failedRow({3, {"[5.0, 0.4]", "sine", "1000", "true"}, {}}, "why");
  EXPECT_EQ(row.at("controller.kd"), Row::parse("[5.0, 0.4]"));
  EXPECT_EQ(row.at("reference.type"), "sine");
  EXPECT_TRUE(row.at("plant.publish_rate").is_number());
  EXPECT_EQ(row.at("plant.publish_rate"), 1000.0);
  EXPECT_EQ(row.at("faults.enabled"), true);
  EXPECT_NE(row.dump().find(R"("controller.kd":[5.0,0.4])"), std::string::npos) << row.dump();
}

// A sweep started before values were typed and resumed now: its old rows
// (strings) and its new rows (values) read back alike, and the table is
// typed throughout.
TEST_F(SweepValues, OldRowsWithTheTextOfTheirValuesAreReadTyped) {
  std::ofstream(out_ / "rows" / "shard-0-of-1.jsonl")
      << R"({"index":0,"controller.kd":"[5.0, 0.4]","reference.type":"sine","plant.publish_rate":1000.0,)"
         R"("faults.enabled":"true","status":"completed"})"
      << "\n"
      << R"({"index":1,"controller.kd":[20.0,2.0],"reference.type":"sine","plant.publish_rate":250.0,)"
         R"("faults.enabled":false,"status":"completed"})"
      << "\n";
  const FinishedRows read = readFinishedRows(out_.string(), 2, true, plan_.param_columns);
  ASSERT_EQ(read.rows.size(), 2u);
  const Row& old = read.rows.at(0);
  EXPECT_EQ(old.at("controller.kd"), Row::parse("[5.0, 0.4]"));
  EXPECT_EQ(old.at("reference.type"), "sine");
  EXPECT_EQ(old.at("plant.publish_rate"), 1000.0);
  EXPECT_EQ(old.at("faults.enabled"), true);
  EXPECT_EQ(read.rows.at(1).at("controller.kd"), Row::parse("[20.0, 2.0]"));
  EXPECT_EQ(read.rows.at(1).at("faults.enabled"), false);
  // Only the parameter columns: a result column's text is never re-read.
  std::ofstream(out_ / "rows" / "shard-0-of-1.jsonl")
      << R"({"index":0,"controller.kd":"[1, 2]","stop_reason":"[1, 2]"})"
      << "\n";
  const FinishedRows one = readFinishedRows(out_.string(), 1, true, {"controller.kd"});
  EXPECT_EQ(one.rows.at(0).at("controller.kd"), Row::parse("[1.0, 2.0]"));
  EXPECT_EQ(one.rows.at(0).at("stop_reason"), "[1, 2]");
  // An old quoted value is the string it held; text not YAML is left as it was.
  Row quoted = Row::parse(R"({"reference.type":"\"a, b\"","controller.kd":"[1, 2"})");
  typeOldParams(quoted, {"reference.type", "controller.kd"});
  EXPECT_EQ(quoted.at("reference.type"), "a, b");
  EXPECT_EQ(quoted.at("controller.kd"), "[1, 2");
}

// sweep.csv: a column per joint of a vector axis, a scalar axis and a string
// axis one column each; sweep.jsonl: lists of numbers.
TEST_F(SweepValues, TheTableHasAColumnPerJointOfAVectorAxis) {
  std::map<long, Row> rows;
  rows[0] = Row::parse(R"({"index":0,"controller.kd":[5.0,0.4],"reference.type":"sine",)"
                       R"("plant.publish_rate":1000.0,"faults.enabled":true,"status":"completed"})");
  rows[1] = Row::parse(R"({"index":1,"controller.kd":[20.0,2.0],"reference.type":"smooth sine, slow",)"
                       R"("plant.publish_rate":250.0,"faults.enabled":false,"status":"completed"})");
  writeSweepTable(out_.string(), plan_, rows);
  const std::string csv = fileText(out_ / "sweep.csv");
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_EQ(header.rfind("index,controller.kd[0],controller.kd[1],reference.type,plant.publish_rate,"
                         "faults.enabled,status,",
                         0),
            0u)
      << header;
  EXPECT_NE(csv.find("\n0,5,0.4,sine,1000,1,completed,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n1,20,2,\"smooth sine, slow\",250,0,completed,"), std::string::npos) << csv;
  const std::string jsonl = fileText(out_ / "sweep.jsonl");
  EXPECT_EQ(Row::parse(jsonl.substr(0, jsonl.find('\n'))).at("controller.kd"), Row::parse("[5.0, 0.4]"));

  // An axis of lists of different sizes, or of lists and numbers: one
  // column, each list as its JSON text (quoted: it holds commas).
  rows[1]["controller.kd"] = 20.0;
  writeSweepTable(out_.string(), plan_, rows);
  const std::string mixed = fileText(out_ / "sweep.csv");
  EXPECT_EQ(mixed.rfind("index,controller.kd,reference.type,", 0), 0u) << mixed;
  EXPECT_NE(mixed.find("\n0,\"[5.0,0.4]\",sine,"), std::string::npos) << mixed;
  EXPECT_NE(mixed.find("\n1,20,"), std::string::npos) << mixed;

  // A failed row without a value (null): its joints' fields empty.
  rows[1]["controller.kd"] = nullptr;
  writeSweepTable(out_.string(), plan_, rows);
  EXPECT_NE(fileText(out_ / "sweep.csv").find("\n1,,,\"smooth sine, slow\","), std::string::npos);
}

// The convergence map names a vector value as its YAML was written.
TEST_F(SweepValues, TheMapsNameAVectorValueAsItWasWritten) {
  plan_.param_columns = {"controller.kd"};
  std::map<long, Row> rows;
  long i = 0;
  for (const char* kd : {"[5, 0.4]", "[20, 2]"}) {
    Row r;
    r["index"] = i;
    r["controller.kd"] = Row::parse(kd);
    r["x0_norm"] = 1.0;
    r["converged"] = true;
    r["convergence_time"] = 0.5;
    r["verdict"] = "met";
    rows[i++] = r;
  }
  const SweepMapFiles maps = writeSweepMapFiles(out_.string(), plan_, rows);
  EXPECT_EQ(maps.convergence_axis, "controller.kd");
  EXPECT_NE(maps.scripts.front().find("set xtics ('[5, 0.4]' 0, '[20, 2]' 1)"), std::string::npos)
      << maps.scripts.front();
  // A map value (a payload) likewise, its keys in the order written.
  plan_.param_columns = {"plant.payload"};
  rows[0]["plant.payload"] = typedParam("{mass: 2.0, com: 0.1}");
  rows[1]["plant.payload"] = typedParam("{mass: 1, com: 0.1}");
  const SweepMapFiles payload = writeSweepMapFiles(out_.string(), plan_, rows);
  EXPECT_NE(payload.scripts.front().find("set xtics ('{mass: 2, com: 0.1}' 0, '{mass: 1, com: 0.1}' 1)"),
            std::string::npos)
      << payload.scripts.front();
}

}  // namespace lagrange::tools::sweep_values_test
