/// @file
/// `lagrange replay --component plant` (tools/replay/replay.hpp).

#include <algorithm>
#include <stdexcept>

#include "plant/plant_lcm.hpp"
#include "plant/scenario_plant.hpp"
#include "tools/replay/replay.hpp"
#include "tools/replay/replay_external.hpp"
#include "tools/replay/replay_gaps.hpp"
#include "tools/replay/replay_log.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"

namespace lagrange::tools {

namespace replay_log {

void chooseTorque(const Opened& o, const lagrange::plant_truth_t& truth, Eigen::MatrixXd& tau) {
  switch (truth.torque_source) {
    case lagrange::plant_truth_t::TORQUE_COMMANDED:
    case lagrange::plant_truth_t::TORQUE_HELD: {
      const auto& state = input(o, o.rec.actuator, truth.input_actuator_tick, transport::kActuatorState,
                                transport::kPlantTruth, truth.header.tick);
      const Eigen::MatrixXd profile = transport::toEigen(state.tau_applied);
      requireTaken(profile.rows(), profile.cols(), tau.rows(), tau.cols(),
                   "the torque of ACTUATOR_STATE tick " + std::to_string(truth.input_actuator_tick));
      if (truth.torque_source == lagrange::plant_truth_t::TORQUE_COMMANDED)
        tau = profile;
      else  // held: the final step of that (late) torque, flat over the period
        tau.rowwise() = Eigen::RowVectorXd(profile.row(profile.rows() - 1));
      return;
    }
    case lagrange::plant_truth_t::TORQUE_ZERO:
      tau.setZero();
      return;
    default: {
      const std::string where = whereIs(o.rec, transport::kPlantTruth, truth.header.tick);
      throw ReplayError("the log's PLANT_TRUTH tick " + std::to_string(truth.header.tick) +
                        (where.empty() ? "" : " (" + where + ")") + " gives torque_source " +
                        std::to_string(truth.torque_source) +
                        "; expected 0 (commanded), 1 (held) or 2 (zero): it does not say which torque the "
                        "plant applied, and outputs before it were replayed");
    }
  }
}

}  // namespace replay_log

namespace {

using namespace replay_log;

// First difference between what the plant recorded at a tick and the replayed sample.
std::string firstDifference(const Opened& o, const lagrange::plant_truth_t& truth,
                            const plant::PlantSample& replayed) {
  const Recorded& rec = o.rec;
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
    d = compare("PLANT_POSITION.q", fitting(o, it->second, transport::kPlantPosition).q,
                transport::toEigen(replayed.position.q));
  if (const auto it = rec.motor.find(k); d.empty() && it != rec.motor.end() && replayed.motor) {
    d = compare("PLANT_MOTOR.q", fitting(o, it->second, transport::kPlantMotor).q,
                transport::toEigen(replayed.motor->q));
    if (d.empty() && it->second.num_rates > 0)
      d = compare("PLANT_MOTOR.qdot", it->second.qdot, transport::toEigen(replayed.motor->qdot));
  }
  if (const auto it = rec.rates.find(k); d.empty() && it != rec.rates.end()) {
    if (!replayed.rate) return "PLANT_RATE: recorded, but the scenario declares no velocity sensor";
    d = compare("PLANT_RATE.qdot", fitting(o, it->second, transport::kPlantRate).qdot,
                transport::toEigen(replayed.rate->qdot));
  }
  return d;
}

}  // namespace

ReplayResult replayPlant(const std::string& log_path, const std::vector<std::string>& overrides,
                         const std::vector<std::string>& external_command) {
  return replayWith(log_path, overrides, transport::kPlantTruth, [&](const Opened& o, ReplayResult& result) {
    const Recorded& rec = o.rec;
    const config::Scenario& s = o.scenario;
    if (s.plant.external()) return replayExternalPlant(o, result, external_command);
    if (!external_command.empty())
      throw ReplayError(
          "the log's plant is simulated, which replay builds itself; a command after -- "
          "replays an external plant (plant.type external) only, and none was run");
    plant::PlantSim sim = plant::plantFor(s);
    plant::ScenarioSensors sensors = plant::sensorsFor(s);  // their draws again, tick by tick
    Eigen::MatrixXd tau = Eigen::MatrixXd::Zero(s.torqueStepsPerTick(), s.dof());
    const lagrange::header_t* previous = nullptr;
    for (const auto& truth : rec.truths) {  // in tick order (openLog)
      requireNoGap(rec, transport::kPlantTruth, OutputSequence::kEveryTick, previous, truth.header,
                   result.commands);
      previous = &truth.header;
      fitting(o, truth, transport::kPlantTruth);
      const int64_t k = truth.header.tick;
      std::string d;
      if (k > 0) {
        chooseTorque(o, truth, tau);
        try {
          sim.stepProfile(tau, s.substepsPerTick());
        } catch (const std::exception& e) {
          d = std::string("PLANT_TRUTH: the replayed plant could not step: ") + e.what();
        }
      }
      if (d.empty()) {
        const auto replayed =
            plant::measureTick(s, sensors, sim, k, static_cast<double>(k) * s.tickPeriod(),
                               tau.row(0).transpose(), {truth.input_actuator_tick, truth.torque_source});
        d = firstDifference(o, truth, replayed);
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
