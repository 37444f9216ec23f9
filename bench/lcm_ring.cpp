/// @file
/// The communication floor: three processes in a ring over LCM, forwarding
/// messages of the sizes a lockstep tick exchanges (PLANT_POSITION,
/// CONTROL_COMMAND, ACTUATOR_STATE), with no computation. Prints rounds per
/// second. Run it inside a private network namespace (bench/run.sh does).
///
/// With --origin-work-us and --listener it is the floor of a lockstep tick
/// rather than of bare messaging: the origin (the plant's place) works that
/// long before each round's first message -- the plant's physics, which is
/// on the tick's path -- and a fourth process receives every message, as
/// the logger does, doing nothing with them.

#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <vector>

#include "actuator/actuator_lcm.hpp"
#include "controller/controller_lcm.hpp"
#include "controller/theorem1.hpp"
#include "plant/plant_lcm.hpp"

namespace {

// Busy for `us` microseconds, as a computation would be (not asleep).
void work(double us) {
  if (us <= 0) return;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double, std::micro>(us);
  while (std::chrono::steady_clock::now() < end) {
  }
}

struct Forwarder {
  lcm::LCM* lcm;
  std::string out_channel;
  std::vector<uint8_t> payload;
  long long remaining;
  double work_us = 0;
  void onMessage(const lcm::ReceiveBuffer*, const std::string&) {
    work(work_us);
    lcm->publish(out_channel, payload.data(), static_cast<unsigned>(payload.size()));
    --remaining;
  }
};

template <class Msg>
std::vector<uint8_t> encode(const Msg& m) {
  std::vector<uint8_t> b(static_cast<size_t>(m.getEncodedSize()));
  m.encode(b.data(), 0, static_cast<int>(b.size()));
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Bare LCM ring of three processes (the lockstep communication floor)", "lagrange-bench-ring"};
  long long rounds = 20000;
  int joints = 2;
  std::string url = "udpm://239.255.76.67:7699?ttl=0";
  app.add_option("--rounds", rounds, "Round trips to time")->capture_default_str();
  app.add_option("--joints", joints, "Joint count the message sizes correspond to")->capture_default_str();
  app.add_option("--lcm-url", url, "LCM URL")->capture_default_str();
  double origin_work_us = 0;
  bool listener = false;
  app.add_option("--origin-work-us", origin_work_us,
                 "Microseconds of busy work at the origin before each round (the plant's physics)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
  app.add_flag("--listener", listener, "A fourth process receives every message (as the logger does)");
  CLI11_PARSE(app, argc, argv);

  // Real messages of this joint count give the real sizes.
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(joints);
  const auto sample = lagrange::plant::plantSample(0, 0.0, zero, zero, zero, 0.0, 0.0, {}, zero);
  lagrange::controller::Theorem1Output out{zero, zero, zero, zero, zero, Eigen::MatrixXd(0, joints)};
  const auto command = lagrange::controller::commandMessage(out, 0, 0.0);
  lagrange::actuator::ActuatorOutput act{zero,
                                         Eigen::Array<bool, Eigen::Dynamic, 1>::Constant(joints, false)};
  const auto state = lagrange::actuator::actuatorMessage(act, Eigen::MatrixXd(0, joints), command);
  const std::vector<uint8_t> pos = encode(sample.position), cmd = encode(command), st = encode(state);

  // Two forwarders: POS -> CMD and CMD -> ACT.
  std::vector<pid_t> children;
  const std::vector<std::tuple<std::string, std::string, std::vector<uint8_t>>> hops = {
      {"RING_POS", "RING_CMD", cmd}, {"RING_CMD", "RING_ACT", st}};
  for (const auto& [in, outc, payload] : hops) {
    const pid_t pid = fork();
    if (pid == 0) {
      lcm::LCM lcm(url);
      Forwarder f{&lcm, outc, payload, rounds};
      lcm.subscribe(in, &Forwarder::onMessage, &f)->setQueueCapacity(1000);
      while (f.remaining > 0)
        if (lcm.handleTimeout(2000) <= 0) break;
      _exit(0);
    }
    children.push_back(pid);
  }
  if (listener) {
    const pid_t pid = fork();
    if (pid == 0) {
      lcm::LCM lcm(url);
      lcm.subscribeFunction(
             ".*", +[](const lcm::ReceiveBuffer*, const std::string&, void*) {}, static_cast<void*>(nullptr))
          ->setQueueCapacity(100000);
      while (lcm.handleTimeout(1000) > 0) {
      }
      _exit(0);  // a second without messages: the ring has ended
    }
    children.push_back(pid);
  }
  // The origin: ACT -> next POS.
  lcm::LCM lcm(url);
  Forwarder origin{&lcm, "RING_POS", pos, rounds, origin_work_us};
  lcm.subscribe("RING_ACT", &Forwarder::onMessage, &origin)->setQueueCapacity(1000);
  usleep(200000);  // let the forwarders subscribe
  const auto start = std::chrono::steady_clock::now();
  lcm.publish("RING_POS", pos.data(), static_cast<unsigned>(pos.size()));
  while (origin.remaining > 1)
    if (lcm.handleTimeout(2000) <= 0) {
      std::fprintf(stderr, "ring stalled after %lld rounds\n", rounds - origin.remaining);
      return 1;
    }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (pid_t p : children) waitpid(p, nullptr, 0);
  std::printf("%.1f\n", static_cast<double>(rounds - 1) / seconds);
  return 0;
}
