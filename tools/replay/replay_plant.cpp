/// @file
/// `lagrange replay --component plant` (tools/replay/replay.hpp).

#include <algorithm>
#include <stdexcept>

#include "plant/plant_lcm.hpp"
#include "plant/scenario_plant.hpp"
#include "tools/replay/replay.hpp"
#include "tools/replay/replay_log.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"

namespace lagrange::tools {

namespace {

using namespace replay_log;

// The torque profile the plant applied over the period ending at `truth`,
// as the sample itself says it was chosen.
std::string chooseTorque(const Recorded& rec, const lagrange::plant_truth_t& truth, Eigen::MatrixXd& tau) {
  switch (truth.torque_source) {
    case lagrange::plant_truth_t::TORQUE_COMMANDED:
    case lagrange::plant_truth_t::TORQUE_HELD: {
      const auto& state = input(rec.actuator, truth.input_actuator_tick, transport::kActuatorState,
                                transport::kPlantTruth, truth.header.tick);
      const Eigen::MatrixXd profile = transport::toEigen(state.tau_applied);
      if (profile.rows() != tau.rows() || profile.cols() != tau.cols())
        return "PLANT_TRUTH: the torque of ACTUATOR_STATE tick " + std::to_string(truth.input_actuator_tick) +
               " is " + std::to_string(profile.rows()) + " x " + std::to_string(profile.cols()) +
               ", the scenario's " + std::to_string(tau.rows()) + " x " + std::to_string(tau.cols());
      if (truth.torque_source == lagrange::plant_truth_t::TORQUE_COMMANDED)
        tau = profile;
      else  // held: the final step of that (late) torque, flat over the period
        tau.rowwise() = Eigen::RowVectorXd(profile.row(profile.rows() - 1));
      return "";
    }
    case lagrange::plant_truth_t::TORQUE_ZERO:
      tau.setZero();
      return "";
    default:
      return "PLANT_TRUTH.torque_source: recorded " + std::to_string(truth.torque_source) +
             ", expected 0 (commanded), 1 (held) or 2 (zero)";
  }
}

// First difference between what the plant recorded at a tick and the replayed sample.
std::string firstDifference(const Recorded& rec, const lagrange::plant_truth_t& truth,
                            const plant::PlantSample& replayed) {
  const lagrange::plant_truth_t& r = replayed.truth;
  std::string d = compare("PLANT_TRUTH.sim_time", truth.header.sim_time, r.header.sim_time);
  if (d.empty()) d = compare("PLANT_TRUTH.q", truth.q, transport::toEigen(r.q));
  if (d.empty()) d = compare("PLANT_TRUTH.qdot", truth.qdot, transport::toEigen(r.qdot));
  if (d.empty()) d = compare("PLANT_TRUTH.tau_applied", truth.tau_applied, transport::toEigen(r.tau_applied));
  if (d.empty()) d = compare("PLANT_TRUTH.kinetic_energy", truth.kinetic_energy, r.kinetic_energy);
  if (d.empty()) d = compare("PLANT_TRUTH.potential_energy", truth.potential_energy, r.potential_energy);
  if (d.empty()) d = compare("PLANT_TRUTH.total_energy", truth.total_energy, r.total_energy);
  const int64_t k = truth.header.tick;
  if (const auto it = rec.positions.find(k); d.empty() && it != rec.positions.end())
    d = compare("PLANT_POSITION.q", it->second.q, transport::toEigen(replayed.position.q));
  if (const auto it = rec.motor.find(k); d.empty() && it != rec.motor.end() && replayed.motor) {
    d = compare("PLANT_MOTOR.q", it->second.q, transport::toEigen(replayed.motor->q));
    if (d.empty() && it->second.num_rates > 0)
      d = compare("PLANT_MOTOR.qdot", it->second.qdot, transport::toEigen(replayed.motor->qdot));
  }
  if (const auto it = rec.rates.find(k); d.empty() && it != rec.rates.end()) {
    if (!replayed.rate) return "PLANT_RATE: recorded, but the scenario declares no velocity sensor";
    d = compare("PLANT_RATE.qdot", it->second.qdot, transport::toEigen(replayed.rate->qdot));
  }
  return d;
}

// The plant's samples by tick: in the log a re-sent one (lost on the way to
// the logger the first time) comes after later ones.
std::vector<lagrange::plant_truth_t> inTickOrder(std::vector<lagrange::plant_truth_t> truths) {
  std::stable_sort(truths.begin(), truths.end(),
                   [](const auto& a, const auto& b) { return a.header.tick < b.header.tick; });
  return truths;
}

}  // namespace

ReplayResult replayPlant(const std::string& log_path, const std::vector<std::string>& overrides) {
  return replayWith(log_path, overrides, transport::kPlantTruth, [&](const Opened& o, ReplayResult& result) {
    const Recorded& rec = o.rec;
    const config::Scenario& s = o.scenario;
    plant::PlantSim sim = plant::plantFor(s);
    plant::ScenarioSensors sensors = plant::sensorsFor(s);  // their draws again, tick by tick
    Eigen::MatrixXd tau = Eigen::MatrixXd::Zero(s.torqueStepsPerTick(), s.dof());
    int64_t expected_tick = 0;
    for (const auto& truth : inTickOrder(rec.truths)) {
      const int64_t k = truth.header.tick;
      if (k != expected_tick)
        throw ReplayError("the log lacks PLANT_TRUTH tick " + std::to_string(expected_tick) +
                          " (the next is " + std::to_string(k) +
                          "); the plant's samples before it were replayed");
      ++expected_tick;
      std::string d;
      if (k > 0) {
        d = chooseTorque(rec, truth, tau);
        if (d.empty()) {
          try {
            sim.stepProfile(tau, s.substepsPerTick());
          } catch (const std::exception& e) {
            d = std::string("PLANT_TRUTH: the replayed plant could not step: ") + e.what();
          }
        }
      }
      if (d.empty()) {
        const auto replayed =
            plant::measureTick(s, sensors, sim, k, static_cast<double>(k) * s.tickPeriod(),
                               tau.row(0).transpose(), {truth.input_actuator_tick, truth.torque_source});
        d = firstDifference(rec, truth, replayed);
      }
      ++result.commands;
      if (!d.empty()) {
        result.divergence = at(k, truth.header.sim_time) + d;
        break;
      }
    }
  });
}

}  // namespace lagrange::tools
