// `lagrange sweep` over a vector gain (issue #54 item 3): the rows give
// `controller.kd` as a list of numbers, not the text "[5.0, 0.4]", and
// sweep.csv a column per joint. A sweep started before values were typed --
// its rows file holding the text -- resumes and collects, typed throughout.
// Two rows of 0.2 s in process: a few seconds.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/sweep_files.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

std::vector<Json> jsonLines(const std::string& path) {
  std::vector<Json> rows;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) rows.push_back(Json::parse(line));
  return rows;
}

TEST(SweepTypedValues, AVectorGainIsAListOfNumbersInTheRowsAndAColumnPerJointInTheTable) {
  const std::string dir = freshDir("sweep-values");
  fs::create_directories(dir);
  std::ofstream(dir + "/sweep.yaml") << "scenario: " << kRigid << "\n"
                                     << "set: {duration: 0.2}\n"
                                     << "axes:\n  - {key: controller.kd, values: [[5.0, 0.4], [20, 2]]}\n";
  const std::string out = dir + "/out";
  const std::string command = "sweep " + quote(dir + "/sweep.yaml") + " -o " + quote(out) + " -j 1";
  const RunResult first = lagrange(command);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  std::vector<Json> rows = jsonLines(out + "/sweep.jsonl");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("controller.kd"), Json::parse("[5.0, 0.4]"));
  EXPECT_EQ(rows[1].at("controller.kd"), Json::parse("[20.0, 2.0]"));
  const std::string csv = readText(out + "/sweep.csv");
  EXPECT_EQ(csv.rfind("index,controller.kd[0],controller.kd[1],status,", 0), 0u) << csv;
  EXPECT_NE(csv.find("\n0,5,0.4,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n1,20,2,"), std::string::npos) << csv;
  const std::string typed_table = tableWithoutWallTime(out);

  // The rows file as a sweep before typed values wrote it: row 0 with the
  // text of its gain, row 1 not yet run.
  const fs::path shard = fs::path(out) / "rows" / "shard-0-of-1.jsonl";
  const std::vector<Json> written = jsonLines(shard.string());
  ASSERT_EQ(written.size(), 2u);
  Json old = written[0].at("index") == 0 ? written[0] : written[1];
  old["controller.kd"] = "[5.0, 0.4]";
  std::ofstream(shard, std::ios::trunc) << old.dump() << "\n";
  fs::remove(out + "/sweep.csv");
  fs::remove(out + "/sweep.jsonl");

  const RunResult resumed = lagrange(command);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("2 runs of"), std::string::npos) << resumed.output;
  EXPECT_NE(resumed.output.find("1 to run"), std::string::npos) << resumed.output;
  rows = jsonLines(out + "/sweep.jsonl");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("controller.kd"), Json::parse("[5.0, 0.4]"));
  EXPECT_EQ(rows[1].at("controller.kd"), Json::parse("[20.0, 2.0]"));
  EXPECT_EQ(tableWithoutWallTime(out), typed_table);

  const RunResult collected = lagrange("sweep collect " + quote(out) + " -q");
  ASSERT_EQ(collected.exit_code, 0) << collected.output;
  EXPECT_EQ(tableWithoutWallTime(out), typed_table);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lagrange::testing
