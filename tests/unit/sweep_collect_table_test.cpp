// `lagrange sweep collect` leaves a sweep's table as it was when it refuses
// something in OUT/rows (issue #53 item 7): before, a rows file refused (here
// the sweep's own rows file turned into a link, beside a planted file of
// rows outside the plan) made collect rewrite a good sweep.csv with 0 rows.
// Collect runs in a child process, as in sweep_collect_test.cpp.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "support/configs.hpp"
#include "tools/sweep/sweep.hpp"
#include "tools/sweep/sweep_plan.hpp"

namespace lagrange::tools::sweep_collect_table_test {

namespace fs = std::filesystem;

std::string bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

struct Collected {
  int exit_code = -1;
  std::string out, err;
};

Collected collectInChild(const fs::path& out_dir) {
  const fs::path out_file = out_dir.string() + ".stdout", err_file = out_dir.string() + ".stderr";
  const pid_t pid = fork();
  if (pid == 0) {
    if (!std::freopen(out_file.c_str(), "w", stdout) || !std::freopen(err_file.c_str(), "w", stderr))
      _exit(99);
    const int code = collectSweep(out_dir.string(), false);
    std::fflush(stdout);
    std::fflush(stderr);
    _exit(code);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  Collected c;
  c.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  c.out = bytesOf(out_file);
  c.err = bytesOf(err_file);
  fs::remove(out_file);
  fs::remove(err_file);
  return c;
}

TEST(SweepCollectTable, ARefusedRowsFileLeavesAGoodTableByteForByte) {
  const fs::path out =
      fs::temp_directory_path() / ("lagrange-unit-collect-table-" + std::to_string(getpid()));
  fs::remove_all(out);
  fs::create_directories(out / "rows");
  SweepPlan plan;
  plan.spec.file = (out / "sweep.yaml").string();
  plan.spec.scenario_path = testing::kRigid;
  plan.spec.scenario_digest = "0";
  plan.param_columns = {"controller.kd"};
  {
    std::ofstream rows(out / "rows" / "shard-0-of-1.jsonl");
    for (int i = 0; i < 4; ++i) {
      const std::string kd = std::to_string(5 * (i + 1));
      plan.rows.push_back({i, {kd}, {"controller.kd=" + kd}});
      rows << "{\"index\":" << i << ",\"controller.kd\":" << kd
           << ".0,\"status\":\"completed\",\"diverged\":false,\"converged\":true,\"convergence_time\":0.5,"
              "\"verdict\":\"met\"}\n";
    }
  }
  std::ofstream(out / "plan.json") << planJson(plan);

  const Collected good = collectInChild(out);
  ASSERT_EQ(good.exit_code, 0) << good.err;
  const std::string csv = bytesOf(out / "sweep.csv"), jsonl = bytesOf(out / "sweep.jsonl");
  const std::string maps = bytesOf(out / "maps" / "maps.gp");
  ASSERT_NE(csv.find("\n3,20,completed"), std::string::npos) << csv;

  // The shard's rows file becomes a link to its own bytes elsewhere (refused:
  // a link, even to a good file), and a planted file adds a row outside the plan.
  fs::rename(out / "rows" / "shard-0-of-1.jsonl", out / "moved.jsonl");
  fs::create_symlink(out / "moved.jsonl", out / "rows" / "shard-0-of-1.jsonl");
  std::ofstream(out / "rows" / "shard-1-of-2.jsonl") << R"({"index":-7,"status":"completed"})"
                                                        "\n";
  const Collected refused = collectInChild(out);
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_NE(refused.err.find("shard-0-of-1.jsonl' is a symbolic link"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("shard-1-of-2.jsonl line 1: index -7 is outside the plan"), std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find((out / "sweep.csv").string() + " and sweep.jsonl were left as they were"),
            std::string::npos)
      << refused.err;
  EXPECT_NE(refused.out.find("0 of 4 runs read from"), std::string::npos) << refused.out;
  EXPECT_EQ(bytesOf(out / "sweep.csv"), csv) << "sweep.csv was rewritten";
  EXPECT_EQ(bytesOf(out / "sweep.jsonl"), jsonl) << "sweep.jsonl was rewritten";
  EXPECT_EQ(bytesOf(out / "maps" / "maps.gp"), maps) << "the maps were redrawn";
  EXPECT_FALSE(fs::exists(out / "sweep.csv.tmp"));
  fs::remove_all(out);
}

}  // namespace lagrange::tools::sweep_collect_table_test
