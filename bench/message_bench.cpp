// Google Benchmark of one message's way through transport::LcmNode in user
// space: publish (stamp, checksum, encode, MAC) then receive (MAC check,
// decode, checksum, run/publisher/sequence admission, validation, handler),
// on LCM's in-process memq:// provider so no kernel time is counted. Each
// hop of a lockstep tick has one of these on its path: its input received,
// its output published (docs/performance.md, "What limits lockstep").
#include <benchmark/benchmark.h>

#include <Eigen/Core>

#include "transport/channels.hpp"
#include "transport/lcm_node.hpp"
#include "transport/messages.hpp"

namespace {

using lagrange::transport::LcmNode;

void BM_PositionPublishAndReceive(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const bool signed_run = state.range(1) != 0;
  LcmNode node("plant", "memq://", 42);
  if (signed_run) node.authenticate(lagrange::transport::MessageKey{1, 2, 3});
  long long handled = 0;
  node.subscribe<lagrange::plant_position_t>(
      lagrange::transport::kPlantPosition,
      [n](const lagrange::plant_position_t& m) { return lagrange::transport::validate(m, n); },
      [&handled](const lagrange::plant_position_t&) { ++handled; });
  lagrange::plant_position_t m{};
  m.num_joints = n;
  m.q.assign(static_cast<size_t>(n), 0.25);
  int64_t tick = 0;
  for (auto _ : state) {
    m.header = lagrange::transport::makeHeader(tick, 0.001 * static_cast<double>(tick));
    ++tick;
    node.publish(lagrange::transport::kPlantPosition, m);
    node.drain(1);
  }
  if (handled != tick) state.SkipWithError("a message was not handled");
}
BENCHMARK(BM_PositionPublishAndReceive)->Args({2, 1})->Args({7, 1})->Args({7, 0});

}  // namespace
