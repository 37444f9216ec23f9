// A sweep's plan in bounded memory (issue #53 item 5): a grid of a million
// rows -- a tenth of the most a sweep may have -- is planned (every
// combination's scenario read, as --dry-run does) holding none of its rows,
// each decoded from its index on demand, and its plan.json written and read
// back a line at a time. Before, a row cost about 500 bytes to 3 KB while
// planning: this grid took some 500 MB, and 10 million rows died with
// std::bad_alloc. Measured in a child process (its peak resident memory,
// reset at its start), so what other tests allocated does not count.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "support/configs.hpp"
#include "tools/sweep/sweep_plan.hpp"
#include "tools/sweep/sweep_plan_file.hpp"

namespace lagrange::tools::sweep_memory_test {

namespace fs = std::filesystem;

// A field of /proc/self/status in kB ("VmRSS:", "VmHWM:"), or -1.
long statusKb(const std::string& field) {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(field, 0) == 0) return std::stol(line.substr(field.size()));
  return -1;
}

struct Measured {
  long rows = 0;
  long held_bytes = 0;   // what the plan's rows hold (SweepRows::heldBytes)
  long peak_growth = 0;  // peak resident memory above the child's start [kB]
  std::string last_row;  // the last row's params and overrides
  std::string failure;
};

// `work` in a child process whose peak resident memory is reset at its start
// (/proc/self/clear_refs 5: VmHWM = VmRSS); what it reports comes back, its
// peak_growth the peak above that start unless `work` measured its own.
Measured inChild(const std::function<Measured()>& work) {
  int fds[2];
  if (pipe(fds) != 0) return {0, 0, 0, "", "pipe failed"};
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    Measured m;
    try {
      std::ofstream("/proc/self/clear_refs") << "5";
      const long start = statusKb("VmRSS:"), reset = statusKb("VmHWM:");
      if (reset > start + 1024)
        throw std::runtime_error("the peak could not be reset (VmHWM " + std::to_string(reset) +
                                 " kB, VmRSS " + std::to_string(start) + " kB)");
      m = work();
      if (m.peak_growth == 0) m.peak_growth = statusKb("VmHWM:") - start;
    } catch (const std::exception& e) {
      m.failure = e.what();
    }
    std::ostringstream out;
    out << m.rows << " " << m.held_bytes << " " << m.peak_growth << "\n" << m.failure << "\n" << m.last_row;
    const std::string text = out.str();
    (void)!write(fds[1], text.data(), text.size());
    _exit(0);
  }
  close(fds[1]);
  std::string text;
  char buf[4096];
  for (ssize_t n; (n = read(fds[0], buf, sizeof buf)) > 0;) text.append(buf, static_cast<size_t>(n));
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  Measured m;
  std::istringstream in(text);
  in >> m.rows >> m.held_bytes >> m.peak_growth;
  in.ignore();
  std::getline(in, m.failure);
  std::getline(in, m.last_row);
  if (!WIFEXITED(status)) m.failure += " (the child died)";
  return m;
}

std::string rowText(const SweepRow& r) {
  std::string s = std::to_string(r.index);
  for (const auto& p : r.params) s += " " + p;
  for (const auto& o : r.overrides) s += " " + o;
  return s;
}

const char* const kMillionRows =
    "set: {duration: 1}\n"
    "axes:\n"
    "  - {key: controller.kd, values: [5, 20]}\n"
    "  - key: initial_state.q\n"
    "    norm: {from: 1.0e-2, to: 1.0e+3, count: 5000, scale: log}\n"
    "    directions: 100\n";

TEST(SweepMemory, AMillionRowGridIsPlannedHoldingNoneOfItsRows) {
  const fs::path dir = fs::temp_directory_path() / ("lagrange-unit-sweep-memory-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path sweep = dir / "sweep.yaml";
  std::ofstream(sweep) << "scenario: " << testing::kRigid << "\n" << kMillionRows;
  const Measured m = inChild([&] {
    const SweepPlan plan = planSweep(readSweepSpec(sweep.string()));
    Measured r;
    r.rows = static_cast<long>(plan.rows.size());
    r.held_bytes = static_cast<long>(plan.rows.heldBytes());
    r.last_row = rowText(plan.rows[plan.rows.size() - 1]);
    return r;
  });
  fs::remove_all(dir);
  ASSERT_EQ(m.failure, "");
  std::cout << "planned " << m.rows << " rows: the rows hold " << m.held_bytes << " bytes, peak memory grew "
            << m.peak_growth << " kB\n";
  EXPECT_EQ(m.rows, 1'000'000);
  // Two combinations of the axes besides the norm: a few hundred bytes, not a million rows of them.
  EXPECT_LT(m.held_bytes, 4096) << "the plan holds its rows";
  // The binary's own pages touched for the first time, the scenarios read:
  // a few MB. Before: about 500 MB.
  EXPECT_LT(m.peak_growth, 32 * 1024)
      << "kB; a million rows cost " << m.peak_growth * 1024 / 1'000'000 << " bytes each while planning";
  // The last row decoded from its index: the last value, the last norm, the last direction.
  EXPECT_EQ(m.last_row.rfind("999999 20 1000 99 duration=1 controller.kd=20 initial_state.q=[", 0), 0u)
      << m.last_row;
}

// plan.json written and read back (as a shard reads it) a line at a time:
// 100 000 rows, 13 MB of text, never held whole.
TEST(SweepMemory, APlanFileIsWrittenAndReadALineAtATime) {
  const fs::path dir =
      fs::temp_directory_path() / ("lagrange-unit-sweep-plan-file-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path sweep = dir / "sweep.yaml";
  std::ofstream(sweep) << "scenario: " << testing::kRigid << "\n"
                       << "axes:\n"
                          "  - key: initial_state.q\n"
                          "    norm: {from: 1.0e-2, to: 1.0e+3, count: 1000, scale: log}\n"
                          "    directions: 100\n";
  const std::string path = (dir / "plan.json").string();
  const Measured m = inChild([&] {
    const SweepPlan plan = planSweep(readSweepSpec(sweep.string()));
    // From here: what writing and reading the file costs.
    std::ofstream("/proc/self/clear_refs") << "5";
    const long planned = statusKb("VmRSS:");
    const std::string written = writePlanFile(plan, path);
    const PlanFile file(path);
    if (file.sha256() != written) throw std::runtime_error("the digest read is not the digest written");
    Measured r;
    r.held_bytes = static_cast<long>(fs::file_size(path));
    const SweepPlan header = file.header();
    file.forEachRow(header, [&](const SweepRow& row) {
      if (row.index % 9973 == 0 && rowText(row) != rowText(plan.rows[static_cast<size_t>(row.index)]))
        throw std::runtime_error("row " + std::to_string(row.index) + " read back differs");
      r.last_row = rowText(row);
      ++r.rows;
      return true;
    });
    r.peak_growth = statusKb("VmHWM:") - planned;
    return r;
  });
  fs::remove_all(dir);
  ASSERT_EQ(m.failure, "");
  std::cout << "wrote and read a plan.json of " << m.rows << " rows, " << m.held_bytes
            << " bytes: peak memory grew " << m.peak_growth << " kB\n";
  EXPECT_EQ(m.rows, 100'000);
  EXPECT_GT(m.held_bytes, 10'000'000) << "bytes of plan.json";
  // Two pieces of 1 MiB, a line and the allocator's own (about 4 MB in all, measured 4.0-4.2 MB);
  // before, the text (12.7 MB) and every row parsed (some 40 MB).
  EXPECT_LT(m.peak_growth * 1024, m.held_bytes / 2) << "kB of peak growth: the plan's text was held";
  EXPECT_EQ(m.last_row.rfind("99999 1000 99 initial_state.q=[", 0), 0u) << m.last_row;
}

}  // namespace lagrange::tools::sweep_memory_test
