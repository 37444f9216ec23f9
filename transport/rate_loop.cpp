#include "transport/rate_loop.hpp"

#include <alloca.h>
#include <malloc.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "util/error.hpp"

namespace lagrange::transport {

int64_t monotonicNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

Percentiles percentiles(std::vector<double> samples) {
  Percentiles p;
  if (samples.empty()) return p;
  std::sort(samples.begin(), samples.end());
  auto at = [&](double q) {
    const size_t i = static_cast<size_t>(std::ceil(q * static_cast<double>(samples.size()))) - 1;
    return samples[std::min(i, samples.size() - 1)];
  };
  p.p50 = at(0.5);
  p.p99 = at(0.99);
  p.max = samples.back();
  return p;
}

FixedRateLoop::FixedRateLoop(double period, double phase)
    : period_ns_(static_cast<int64_t>(std::llround(period * 1e9))),
      phase_ns_(static_cast<int64_t>(std::llround(phase * period * 1e9))) {
  if (period_ns_ <= 0) throw std::invalid_argument("FixedRateLoop: period must be positive");
  if (phase < 0.0 || phase >= 1.0) throw std::invalid_argument("FixedRateLoop: phase must be in [0, 1)");
}

void setInputStats(lagrange::loop_stats_t& stats, const SampleHistogram& ages, int64_t missing,
                   int64_t stale) {
  const Percentiles a = ages.percentiles();
  stats.input_age_p50 = a.p50;
  stats.input_age_p99 = a.p99;
  stats.input_age_max = a.max;
  stats.missing_inputs = missing;
  stats.stale_inputs = stale;
}

namespace {
// Touches `bytes` of stack below the caller, so that the pages a loop's
// deepest call reaches are mapped (and, under mlockall, locked) before the
// loop starts rather than faulted in on its first deep call.
__attribute__((noinline)) void prefaultStack(size_t bytes) {
  volatile unsigned char* page = static_cast<unsigned char*>(alloca(bytes));
  for (size_t i = 0; i < bytes; i += 4096) page[i] = 0;
}

// Makes the heap keep what it is given: no block from mmap (each would be
// faulted in and given back), no trimming of freed memory; then grows the
// heap by `bytes` and frees it, so that later allocations reuse pages that
// are already mapped and locked -- the recipe of the Linux realtime wiki
// ("Memory for Real-time Applications").
void prefaultHeap(size_t bytes) {
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, -1);
  auto* block = static_cast<unsigned char*>(std::malloc(bytes));
  if (block == nullptr) return;
  for (size_t i = 0; i < bytes; i += 4096) block[i] = 1;
  std::free(block);
}
}  // namespace

std::string enterRealtimeScheduling(int priority) {
  if (priority <= 0) return "other";
  sched_param param{};
  param.sched_priority = priority;
  if (sched_setscheduler(0, SCHED_FIFO, &param) != 0) return "other";
  // No page faults inside the loops: memory locked, the stack and a heap
  // reserve mapped now (8 MiB: a loop's messages and Eigen temporaries).
  // Only with the memory locked: under a tight RLIMIT_MEMLOCK, growing the
  // stack by half a megabyte could fail where it stands.
  if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
    prefaultStack(512 * 1024);
    prefaultHeap(8 * 1024 * 1024);
  }
  return "fifo:" + std::to_string(priority);
}

// "0,2-3" for the CPUs of `set`.
std::string cpuList(const cpu_set_t& set) {
  std::string out;
  for (int c = 0; c < CPU_SETSIZE; ++c) {
    if (!CPU_ISSET(c, &set) || (c > 0 && CPU_ISSET(c - 1, &set))) continue;
    int last = c;
    while (last + 1 < CPU_SETSIZE && CPU_ISSET(last + 1, &set)) ++last;
    out += (out.empty() ? "" : ",") + std::to_string(c) + (last > c ? "-" + std::to_string(last) : "");
  }
  return out;
}

namespace {
// Set once this process pinned itself: its loops then report where.
bool g_pinned = false;
}  // namespace

void checkCpus(const std::vector<int>& cpus, const std::string& key) {
  // The CPUs this process may use: the online ones, less what a container's
  // cpuset or a taskset took away (offline CPUs are never in the set).
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0)
    throw BadInput(key + ": cannot read this process's CPUs (" + std::strerror(errno) + ")");
  for (const int c : cpus)
    if (c < 0 || c >= CPU_SETSIZE || !CPU_ISSET(c, &allowed))
      throw BadInput(key + ": CPU " + std::to_string(c) + " is not among this machine's CPUs " +
                     cpuList(allowed) + " (those this process may use); expected CPU numbers it has");
}

void pinToCpus(const std::vector<int>& cpus, const std::string& key) {
  checkCpus(cpus, key);
  cpu_set_t set;
  CPU_ZERO(&set);
  for (const int c : cpus) CPU_SET(c, &set);
  if (sched_setaffinity(0, sizeof set, &set) != 0)
    throw BadInput(key + ": the kernel refused CPUs " + cpuList(set) + " (" + std::strerror(errno) +
                   "; a container's cpuset may allow fewer); expected CPUs this process may use");
  g_pinned = true;
}

std::string cpuRestriction() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (!g_pinned || sched_getaffinity(0, sizeof set, &set) != 0) return "";
  return cpuList(set);
}

void FixedRateLoop::start() {
  sched_param param{};
  sched_getparam(0, &param);
  scheduler_ = sched_getscheduler(0) == SCHED_FIFO ? "fifo:" + std::to_string(param.sched_priority) : "other";
  if (const std::string cpus = cpuRestriction(); !cpus.empty()) scheduler_ += " cpus " + cpus;
  // The kernel's default 50 us timer slack would show up as 50 us of jitter
  // on every wake-up; a realtime loop asks for none.
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  start_ns_ = monotonicNs();
  const int64_t k = (start_ns_ - phase_ns_) / period_ns_ + 1;
  next_ns_ = k * period_ns_ + phase_ns_;
}

void FixedRateLoop::waitNext() {
  const int64_t now = monotonicNs();
  if (now > next_ns_) {
    ++misses_;
    longest_miss_run_ = std::max(longest_miss_run_, ++miss_run_);
  } else {
    miss_run_ = 0;
    timespec deadline{static_cast<time_t>(next_ns_ / 1000000000LL),
                      static_cast<long>(next_ns_ % 1000000000LL)};
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr) == EINTR) {
    }
  }
  lateness_.add(static_cast<double>(std::max<int64_t>(0, monotonicNs() - next_ns_)) * 1e-9);
  ++cycles_;
  next_ns_ += period_ns_;
}

lagrange::loop_stats_t FixedRateLoop::stats() const {
  lagrange::loop_stats_t s{};
  s.period = static_cast<double>(period_ns_) * 1e-9;
  s.scheduler = scheduler_;
  s.cycles = cycles_;
  const double elapsed = static_cast<double>(monotonicNs() - start_ns_) * 1e-9;
  s.achieved_rate = elapsed > 0.0 ? static_cast<double>(cycles_) / elapsed : 0.0;
  const Percentiles j = lateness_.percentiles();
  s.jitter_p50 = j.p50;
  s.jitter_p99 = j.p99;
  s.jitter_max = j.max;
  s.deadline_misses = misses_;
  s.longest_miss_run = longest_miss_run_;
  return s;
}

}  // namespace lagrange::transport
