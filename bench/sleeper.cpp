/// @file
/// `lagrange-bench-sleeper`: the machine's own ceiling for the realtime
/// loops. Three threads -- as many as a realtime run has loops, at the same
/// phases (plant 0, controller 0.25, actuator 0.5 of a period) -- run the
/// same transport::FixedRateLoop under the same SCHED_FIFO priority and
/// locked memory, and do nothing but sleep to their deadlines. What they miss
/// is the machine's (timer, scheduler, other load), not the project's;
/// bench_runner sets each loop of a run beside it. Prints one JSON object:
/// {"plant": {"on_time_fraction", "longest_miss_run", "cycles", "jitter_p99", "jitter_max"}, ...}.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "transport/rate_loop.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Three bare fixed-rate loops under SCHED_FIFO: the machine's realtime ceiling",
               "lagrange-bench-sleeper"};
  double period = 1e-3, seconds = 10.0;
  int priority = 50;
  app.add_option("--period", period, "Loop period [s]")->capture_default_str();
  app.add_option("--seconds", seconds, "How long to run [s]")->capture_default_str();
  app.add_option("--priority", priority, "SCHED_FIFO priority (0: the normal scheduler)")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  // Before any thread: the threads inherit the policy (as the processes' do).
  const std::string scheduler = lagrange::transport::enterRealtimeScheduling(priority);
  const std::vector<std::pair<std::string, double>> loops = {
      {"plant", 0.0}, {"controller", 0.25}, {"actuator", 0.5}};
  std::vector<lagrange::loop_stats_t> stats(loops.size());
  std::vector<std::thread> threads;
  const auto cycles = static_cast<long long>(seconds / period);
  for (size_t i = 0; i < loops.size(); ++i)
    threads.emplace_back([&, i] {
      lagrange::transport::FixedRateLoop loop(period, loops[i].second);
      loop.start();
      for (long long k = 0; k < cycles; ++k) loop.waitNext();
      stats[i] = loop.stats();
    });
  for (auto& t : threads) t.join();
  nlohmann::json out;
  for (size_t i = 0; i < loops.size(); ++i) {
    const auto& s = stats[i];
    out[loops[i].first] = {
        {"on_time_fraction",
         s.cycles > 0 ? 1.0 - static_cast<double>(s.deadline_misses) / static_cast<double>(s.cycles) : 0.0},
        {"longest_miss_run", s.longest_miss_run},
        {"cycles", s.cycles},
        {"jitter_p99", s.jitter_p99},
        {"jitter_max", s.jitter_max},
        {"scheduler", scheduler}};
  }
  std::printf("%s\n", out.dump().c_str());
  return 0;
}
