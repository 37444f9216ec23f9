/// @file
/// The plant process: stands in for the robot. Simulates the arm in ODE and
/// drives the lockstep clock of the run.
///
///   for tick k = 0..N:
///     wait until the logger is at most lockstep.logger_window ticks behind
///     publish PLANT_POSITION (q) and PLANT_TRUTH (q, q', energy) for tick k
///     wait for ACTUATOR_STATE of tick k (re-sending tick k after
///       lockstep.retransmit_timeout without an answer)
///     apply its torque for one period (physics sub-steps; not after tick N)
///   publish STATUS "finished"

#include <spdlog/spdlog.h>

#include <chrono>

#include "plant/plant_sim.hpp"
#include "transport/builders.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"
#include "transport/process.hpp"

namespace lagrange {
namespace {

using Clock = std::chrono::steady_clock;

transport::PlantSample sample(const plant::PlantSim& sim, int64_t tick, double sim_time,
                              const Eigen::VectorXd& tau_applied) {
  const plant::PlantState st = sim.state();
  const plant::PlantEnergy e = sim.energy();
  return transport::plantSample(tick, sim_time, st.q, st.qdot, tau_applied, e.kinetic, e.potential);
}

int DoMain(int argc, char** argv) {
  double startup_timeout = 30.0;
  return transport::runProcess(
      "plant", "ODE simulation of the robot arm; drives the lockstep clock.", argc, argv,
      [&](CLI::App& app) {
        app.add_option("--startup-timeout", startup_timeout,
                       "Seconds to wait for the logger before giving up")
            ->capture_default_str();
      },
      [&](const config::Scenario& s, transport::LcmNode& node) {
        plant::PlantSim sim(s.robot, {s.initial_state.q, s.initial_state.qdot}, s.plant.physics_step);
        const int n = s.dof();
        const int substeps = s.substepsPerTick();
        const int64_t last_tick = s.lastTick();
        const auto retransmit = std::chrono::duration<double>(s.lockstep.retransmit_timeout);
        transport::StatusReporter status(node);

        int64_t awaited_tick = -1;
        bool answered = false;
        Eigen::VectorXd tau = Eigen::VectorXd::Zero(n);
        node.subscribe<lagrange::actuator_state_t>(
            transport::kActuatorState, [n](const auto& m) { return transport::validate(m, n); },
            [&](const lagrange::actuator_state_t& m) {
              if (m.header.tick != awaited_tick || answered) return;  // stale or duplicate
              tau = transport::toEigen(m.tau_applied);
              answered = true;
            });
        int64_t logger_tick = -2;  // -2: no logger heard yet
        node.subscribe<lagrange::status_t>(
            transport::kStatus, [](const auto& m) { return transport::validate(m); },
            [&](const lagrange::status_t& m) {
              if (m.process == "logger") logger_tick = std::max(logger_tick, m.last_tick);
            });

        status.publish("ready", -1, 0.0);
        const auto startup_deadline = Clock::now() + std::chrono::duration<double>(startup_timeout);
        long long retransmits = 0;
        auto next_status = Clock::now();
        for (int64_t k = 0; k <= last_tick; ++k) {
          const double t = static_cast<double>(k) * s.tickPeriod();
          while (logger_tick == -2 || k - logger_tick > s.lockstep.logger_window) {
            if (transport::stopRequested()) break;
            if (logger_tick == -2 && Clock::now() > startup_deadline)
              throw std::runtime_error("no STATUS from the logger within " + std::to_string(startup_timeout) +
                                       " s; is it running on the same LCM URL?");
            node.handle(20);
          }
          if (transport::stopRequested()) {
            status.publish("interrupted", k - 1, t);
            return 0;
          }
          const transport::PlantSample out = sample(sim, k, t, tau);
          node.publish(transport::kPlantPosition, out.position);
          node.publish(transport::kPlantTruth, out.truth);
          if (Clock::now() >= next_status) {
            status.publish("running", k, t);
            next_status = Clock::now() + std::chrono::milliseconds(500);
          }
          awaited_tick = k;
          answered = false;
          auto resend_at = Clock::now() + retransmit;
          while (!answered && !transport::stopRequested()) {
            node.handle(5);
            if (!answered && Clock::now() >= resend_at) {
              node.publish(transport::kPlantPosition, out.position);
              ++retransmits;
              resend_at = Clock::now() + retransmit;
            }
          }
          if (transport::stopRequested()) {
            status.publish("interrupted", k, t);
            return 0;
          }
          // The last tick's command is awaited too, so every message of the
          // ring is delivered before the plant reports "finished".
          if (k < last_tick) sim.step(tau, substeps);
        }
        if (retransmits > 0) spdlog::info("re-sent {} position samples after timeouts", retransmits);
        status.publish("finished", last_tick, static_cast<double>(last_tick) * s.tickPeriod(), std::nan(""),
                       "retransmits=" + std::to_string(retransmits));
        return 0;
      });
}

}  // namespace
}  // namespace lagrange

int main(int argc, char** argv) { return lagrange::DoMain(argc, argv); }
