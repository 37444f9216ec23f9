// Google Benchmark of `lagrange check-gains` for the shipped planar scenarios
// (issue #55, Performance): the check as the command computes it -- the
// scenario loaded, the gain conditions with the linearised sampled-data
// check, and the sampled loop simulated against the fine-rate one -- in
// process, wall-clock time (the simulations run on threads). Beside it, one
// in-process simulation of each scenario as configured: the unit the check
// is made of (docs/performance.md, "check-gains"). Timing is never asserted.
//
//   build/bin/lagrange-bench-check-gains --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//   build/bin/lagrange-bench-check-gains --benchmark_filter=CheckGains/rigid_2dof
//
// Whole commands of two builds side by side, alternating: bench/check_gains_side_by_side.sh.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "controller/gain_report.hpp"
#include "wiring/inproc_runner.hpp"
#include "wiring/sampled_simulation.hpp"

namespace {

namespace fs = std::filesystem;
using lagrange::config::Scenario;

// Every shipped scenario whose arm is a planar chain (not a URDF arm), by file name.
std::vector<fs::path> planarConfigs() {
  std::vector<fs::path> out;
  for (const fs::directory_entry& e : fs::directory_iterator(fs::path(LAGRANGE_SOURCE_DIR) / "configs")) {
    if (e.path().extension() != ".yaml") continue;
    try {
      if (lagrange::config::loadScenario(e.path().string()).robotModel()->kind() == "planar_chain")
        out.push_back(e.path());
    } catch (const std::exception&) {  // not a scenario file: not benchmarked
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// What `lagrange check-gains CONFIG` computes, printing aside.
void checkGains(benchmark::State& state, const fs::path& config, int jobs) {
  for (auto _ : state) {
    const Scenario s = lagrange::config::loadScenario(config.string());
    lagrange::controller::GainReport r = lagrange::controller::checkGains(s);
    r.simulated = lagrange::wiring::simulateSampledData(s, jobs);
    benchmark::DoNotOptimize(r.simulated->verdict);
  }
}

// One in-process simulation of the scenario as configured, no log.
void oneLoop(benchmark::State& state, const fs::path& config) {
  const Scenario s = lagrange::config::loadScenario(config.string());
  for (auto _ : state) {
    const lagrange::wiring::InProcessOutcome o =
        lagrange::wiring::simulateInProcess(s, nullptr, nullptr, nullptr);
    benchmark::DoNotOptimize(o.tracking);
  }
}

}  // namespace

int main(int argc, char** argv) {
  for (const fs::path& config : planarConfigs()) {
    const std::string name = config.stem().string();
    // jobs 0: one thread per core, as check-gains runs it; 1: the same on one thread.
    for (const int jobs : {0, 1})
      benchmark::RegisterBenchmark(("CheckGains/" + name + "/jobs:" + std::to_string(jobs)).c_str(),
                                   checkGains, config, jobs)
          ->Unit(benchmark::kSecond)
          ->UseRealTime()
          ->Iterations(1);
    benchmark::RegisterBenchmark(("OneLoop/" + name).c_str(), oneLoop, config)
        ->Unit(benchmark::kSecond)
        ->UseRealTime()
        ->Iterations(1);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
