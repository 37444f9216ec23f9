// `lagrange sweep collect` on a crafted sweep folder (a shared Slurm folder
// is writable by others): every file of OUT is read without trusting it
// (tools/sweep/sweep_files.hpp) and every row is held to the plan
// (tools/sweep/sweep_store.hpp). Each attack is the input of a test: a row
// nested 200 000 deep (was SIGSEGV), rows files linked to /dev/zero or
// /dev/urandom, a FIFO (was a hang or 2.1 GB), indices outside the plan and
// 200 000 rows for a 2-row plan (were written into sweep.csv, exit 0, "3 of
// 2 runs"). Collect runs in a child process, so a crash or a hang is a
// failure of the test, not of the test program.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "support/configs.hpp"
#include "tools/sweep/sweep.hpp"
#include "tools/sweep/sweep_plan.hpp"
#include "tools/sweep/sweep_store.hpp"
#include "util/output_file.hpp"

namespace lagrange::tools {
namespace {

namespace fs = std::filesystem;

std::string textOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// An OUT of a finished 4-row sweep: plan.json and the rows of its runs, as
// one shard wrote them.
class SweepCollectTest : public ::testing::Test {
 protected:
  void SetUp() override {
    out_ = fs::temp_directory_path() / ("lagrange-unit-collect-" + std::to_string(getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(out_);
    fs::create_directories(out_ / "rows");
    SweepPlan plan;
    plan.spec.file = (out_ / "sweep.yaml").string();
    plan.spec.scenario_path = testing::kRigid;
    plan.spec.scenario_digest = "0";
    plan.param_columns = {"controller.kd"};
    std::ofstream rows(out_ / "rows" / "shard-0-of-1.jsonl");
    for (int i = 0; i < 4; ++i) {
      const std::string kd = std::to_string(5 * (i + 1));
      plan.rows.push_back({i, {kd}, {"controller.kd=" + kd}});
      rows << "{\"index\":" << i << ",\"controller.kd\":" << kd
           << ".0,\"status\":\"completed\",\"diverged\":false,\"converged\":true}\n";
    }
    std::ofstream(out_ / "plan.json") << planJson(plan);
  }
  void TearDown() override { fs::remove_all(out_); }

  struct Outcome {
    int exit_code = -1;  ///< -1: killed by a signal or still running at the deadline
    std::string how;     ///< "exit 2", "signal 11 (Segmentation fault)", "hung"
    std::string out, err;
  };

  // collectSweep(OUT) in a child process, given `seconds`.
  Outcome collect(double seconds = 20) {
    const fs::path out_file = out_.string() + ".stdout", err_file = out_.string() + ".stderr";
    const pid_t pid = fork();
    if (pid == 0) {
      if (!std::freopen(out_file.c_str(), "w", stdout) || !std::freopen(err_file.c_str(), "w", stderr))
        _exit(99);
      const int code = collectSweep(out_.string(), false);
      std::fflush(stdout);
      std::fflush(stderr);
      _exit(code);
    }
    Outcome o;
    int status = 0;
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (waitpid(pid, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > end) {
        kill(pid, SIGKILL);
        waitpid(pid, &status, 0);
        o.how = "hung (killed after " + std::to_string(seconds) + " s)";
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (o.how.empty() && WIFEXITED(status)) {
      o.exit_code = WEXITSTATUS(status);
      o.how = "exit " + std::to_string(o.exit_code);
    } else if (o.how.empty()) {
      o.how = "signal " + std::to_string(WTERMSIG(status)) + " (" + strsignal(WTERMSIG(status)) + ")";
    }
    o.out = textOf(out_file);
    o.err = textOf(err_file);
    fs::remove(out_file);
    fs::remove(err_file);
    return o;
  }

  // The indices in sweep.csv, in order.
  std::vector<std::string> tableIndices() {
    std::ifstream in(out_ / "sweep.csv");
    std::vector<std::string> indices;
    std::string line;
    std::getline(in, line);  // the header
    while (std::getline(in, line)) indices.push_back(line.substr(0, line.find(',')));
    return indices;
  }

  std::string rows(const std::string& name) const { return (out_ / "rows" / name).string(); }

  fs::path out_;
};

const std::vector<std::string> kEveryRow = {"0", "1", "2", "3"};

TEST_F(SweepCollectTest, AnHonestFolderGivesItsTableAndExitZero) {
  const Outcome o = collect();
  EXPECT_EQ(o.exit_code, 0) << o.how << "\n" << o.err;
  EXPECT_NE(o.out.find("4 of 4 runs in"), std::string::npos) << o.out;
  EXPECT_EQ(tableIndices(), kEveryRow);
}

// The issue's row, 200 000 levels deep, was a SIGSEGV (nlohmann writes a
// value out again recursively); now its file is refused (too large to hold
// rows of this plan), and a row 20 000 deep in a file of a sane size is
// refused by its depth, before a value is built. Rows 0 and 1 are not done,
// so these would be the rows taken.
TEST_F(SweepCollectTest, ARowNestedDeeperThanAnyRowIsRefusedNotACrash) {
  std::ofstream(rows("shard-0-of-1.jsonl")) << "{\"index\":2,\"status\":\"completed\"}\n"
                                            << "{\"index\":3,\"status\":\"completed\"}\n";
  std::ofstream(rows("shard-0-of-2.jsonl"))
      << R"({"index":0,"x":)" << std::string(200000, '[') << std::string(200000, ']') << "}\n";
  std::ofstream(rows("shard-1-of-2.jsonl"))
      << R"({"index":1,"x":)" << std::string(20000, '[') << std::string(20000, ']') << "}\n";
  const Outcome o = collect();
  EXPECT_EQ(o.exit_code, 2) << o.how << "\n" << o.err.substr(0, 2000);
  EXPECT_NE(
      o.err.find("'" + rows("shard-0-of-2.jsonl") +
                 "' holds 400017 bytes; expected a rows file of lagrange sweep of at most 327680 bytes; its "
                 "rows were not read"),
      std::string::npos)
      << o.err.substr(0, 2000);
  EXPECT_NE(o.err.find(rows("shard-1-of-2.jsonl") + " line 1: nested deeper than 32 levels"),
            std::string::npos)
      << o.err.substr(0, 2000);
  EXPECT_NE(o.out.find("2 of 4 runs in"), std::string::npos) << o.out;
  EXPECT_EQ(tableIndices(), (std::vector<std::string>{"2", "3"}));
}

TEST_F(SweepCollectTest, RowsFilesThatAreLinksFifosOrDevicesAreRefusedUnread) {
  fs::create_symlink("/dev/zero", rows("shard-0-of-2.jsonl"));
  fs::create_symlink("/dev/urandom", rows("shard-1-of-2.jsonl"));
  fs::create_symlink(rows("shard-0-of-1.jsonl"), rows("shard-0-of-3.jsonl"));  // a link even to a good file
  ASSERT_EQ(mkfifo(rows("shard-1-of-3.jsonl").c_str(), 0600), 0);
  fs::create_directories(rows("shard-2-of-3.jsonl"));
  std::ofstream(rows("extra.jsonl")) << R"({"index":0,"status":"diverged"})"
                                        "\n";
  const Outcome o = collect();
  EXPECT_EQ(o.exit_code, 2) << o.how << "\n" << o.err;
  for (const char* name : {"shard-0-of-2.jsonl", "shard-1-of-2.jsonl", "shard-0-of-3.jsonl"})
    EXPECT_NE(o.err.find("'" + rows(name) + "' is a symbolic link; expected a rows file of lagrange sweep"),
              std::string::npos)
        << o.err;
  EXPECT_NE(o.err.find(
                "'" + rows("shard-1-of-3.jsonl") +
                "' is a FIFO (named pipe); expected a rows file of lagrange sweep (a regular file); its rows "
                "were not read"),
            std::string::npos)
      << o.err;
  EXPECT_NE(o.err.find("'" + rows("shard-2-of-3.jsonl") + "' is a directory"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find(
                "'" + rows("extra.jsonl") +
                "' is not named as a shard of this sweep writes its rows; expected shard-K-of-N.jsonl with 0 "
                "<= K < N <= 4"),
            std::string::npos)
      << o.err;
  EXPECT_NE(o.out.find("4 of 4 runs in"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("; 6 refused (above)"), std::string::npos) << o.out;
  EXPECT_EQ(tableIndices(), kEveryRow);
}

// In a shared folder, a rows file of another user than the plan's is not
// the sweep's (root only: a test cannot give a file away otherwise).
TEST_F(SweepCollectTest, ARowsFileOfAnotherUserIsRefused) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to give a file to another user";
  std::ofstream(rows("shard-1-of-2.jsonl")) << R"({"index":1,"status":"diverged"})"
                                               "\n";
  ASSERT_EQ(chown(rows("shard-1-of-2.jsonl").c_str(), 65534, 65534), 0);
  fs::remove(rows("shard-0-of-1.jsonl"));  // the other user's row would be the only one
  const Outcome o = collect();
  EXPECT_EQ(o.exit_code, 2) << o.how << "\n" << o.err;
  EXPECT_NE(o.err.find(
                "'" + rows("shard-1-of-2.jsonl") +
                "' belongs to user 65534; expected a rows file of lagrange sweep, which belongs to user 0 as "
                "the sweep's plan.json does; its rows were not read"),
            std::string::npos)
      << o.err;
  EXPECT_NE(o.out.find("0 of 4 runs in"), std::string::npos) << o.out;
}

TEST_F(SweepCollectTest, APlanJsonThatIsAFifoIsRefusedNotWaitedFor) {
  fs::remove(out_ / "plan.json");
  ASSERT_EQ(mkfifo((out_ / "plan.json").c_str(), 0600), 0);
  const Outcome o = collect();
  EXPECT_EQ(o.exit_code, 2) << o.how << "\n" << o.err;
  EXPECT_NE(o.err.find("plan.json' is a FIFO (named pipe); expected the plan.json lagrange sweep wrote"),
            std::string::npos)
      << o.err;
}

TEST_F(SweepCollectTest, RowsOutsideThePlanOrTwiceAreRefusedAndNamedAndTheVerdictIsHonest) {
  std::ofstream(rows("shard-1-of-2.jsonl")) << R"({"index":-7,"status":"completed"})"
                                               "\n"
                                            << R"({"index":99999999999,"status":"completed"})"
                                               "\n"
                                            << R"({"index":1e300,"status":"completed"})"
                                               "\n"
                                            << R"({"index":"1","status":"completed"})"
                                               "\n"
                                            << R"({"index":5,"status":"completed"})"
                                               "\n"
                                            << R"({"index":2,"status":"completed"})"
                                               "\n"
                                            << R"({"index":1,"status":"diverged","diverged":true})"
                                               "\n"
                                            << R"([1,2,3])"
                                               "\n"
                                            << R"({"status":"completed"})"
                                               "\n"
                                            << "not json\n";
  const Outcome o = collect();
  EXPECT_EQ(o.exit_code, 2) << o.how << "\n" << o.err;
  const std::string evil = rows("shard-1-of-2.jsonl");
  const std::string expected = "; expected a whole number from 0 to 3 (the plan has 4 rows)";
  for (const std::string& named :
       {evil + " line 1: index -7 is outside the plan" + expected,
        evil + " line 2: index 99999999999 is outside the plan" + expected,
        evil + " line 3: index 1e+300 is not a whole number" + expected,
        evil + " line 4: index \"1\" is not a whole number" + expected,
        evil + " line 5: index 5 is outside the plan" + expected,
        evil + " line 6: index 2 is not a row of shard 1 of 2; expected an index whose remainder by 2 is 1",
        evil + " line 7: row 1 again (first in " + rows("shard-0-of-1.jsonl") +
            " line 2); expected each row once",
        evil + " line 8: a JSON array, not a row; expected an object with an index",
        evil + " line 9: no index; expected a row with its index", evil + " line 10: not JSON ("})
    EXPECT_NE(o.err.find(named), std::string::npos) << named << "\n" << o.err;
  EXPECT_NE(o.out.find("4 of 4 runs in"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("; 10 refused (above)"), std::string::npos) << o.out;
  EXPECT_EQ(tableIndices(), kEveryRow);
  EXPECT_EQ(textOf(out_ / "sweep.csv").find("diverged,1"), std::string::npos) << "the duplicate was taken";
}

TEST_F(SweepCollectTest, TwoHundredThousandRowsForAFourRowPlanAreRefusedUnread) {
  {
    std::ofstream many(rows("shard-0-of-2.jsonl"));
    for (long i = 0; i < 200000; ++i) many << "{\"index\":" << 2 * i + 4 << ",\"status\":\"completed\"}\n";
  }
  const long long size = static_cast<long long>(fs::file_size(rows("shard-0-of-2.jsonl")));
  const Outcome o = collect();
  EXPECT_EQ(o.exit_code, 2) << o.how << "\n" << o.err;
  EXPECT_NE(
      o.err.find("'" + rows("shard-0-of-2.jsonl") + "' holds " + std::to_string(size) +
                 " bytes; expected a rows file of lagrange sweep of at most 327680 bytes; its rows were not "
                 "read"),
      std::string::npos)
      << o.err;
  EXPECT_NE(o.out.find("4 of 4 runs in"), std::string::npos) << o.out;
  EXPECT_EQ(tableIndices(), kEveryRow);
}

// A shard appends to rows/shard-K-of-N.jsonl after cutting a partial last
// line: through a link planted there it would cut and append to the
// target, any file of the user's. It refuses the link, and the file is untouched.
TEST_F(SweepCollectTest, AShardNeverWritesThroughALinkPlantedAsItsRowsFile) {
  const fs::path victim = out_ / "victim.txt";
  std::ofstream(victim) << "the user's file\nwithout a final newline";
  fs::create_symlink(victim, rows("shard-0-of-2.jsonl"));
  try {
    RowWriter writer(rows("shard-0-of-2.jsonl"));
    ADD_FAILURE() << "the link was opened";
  } catch (const util::UnsafeOutputPath& e) {
    EXPECT_NE(std::string(e.what()).find("'" + rows("shard-0-of-2.jsonl") + "' is a symbolic link"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(textOf(victim), "the user's file\nwithout a final newline");
}

}  // namespace
}  // namespace lagrange::tools
