#include "wiring/inproc_runner.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "actuator/actuator_lcm.hpp"
#include "actuator/integrator_chain.hpp"
#include "config/robot_description_lcm.hpp"
#include "config/scenario_lcm.hpp"
#include "controller/controller_lcm.hpp"
#include "controller/gain_report.hpp"
#include "controller/registry.hpp"
#include "logger/event_log.hpp"
#include "logger/summary.hpp"
#include "logger/tracking_metrics.hpp"
#include "plant/plant_lcm.hpp"
#include "plant/scenario_plant.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"
#include "util/terminal_text.hpp"
#include "wiring/progress.hpp"

namespace lagrange::wiring {

InProcessOutcome simulateInProcess(const config::Scenario& s, logger::EventLog* log,
                                   ProgressDisplay* progress, bool (*stop_requested)(), TickWatch* watch) {
  const auto wall_start = std::chrono::steady_clock::now();
  // Every message is built either way (the controller reads its inputs from
  // them); only the writing is skipped without a log.
  const auto record = [log](const std::string& channel, const auto& msg, int64_t utime) {
    if (log) {
      log->writeMessage(channel, msg, utime);
      log->check();  // a full disk stops the run here, naming run.lcm
    }
  };
  if (log) {
    log->writeMessage(transport::kScenario, config::scenarioMessage(s), transport::nowUtime());
    log->writeMessage(transport::kRobotDescription, config::robotDescriptionMessage(s),
                      transport::nowUtime());
  }

  plant::PlantSim sim = plant::plantFor(s);
  plant::ScenarioSensors sensors = plant::sensorsFor(s);
  const std::unique_ptr<controller::Controller> ctl = controller::makeController(s);
  const controller::Needs needs = ctl->needs();
  // The controller's inputs by the controller process's own rule (lockstep).
  controller::InputAssembly assembly = controller::makeInputAssembly(s, needs);
  actuator::IntegratorChain act(s.dof(), s.actuator.order, s.actuator.saturation, s.actuator.initial_state);
  logger::TrackingMetrics metrics(model::Reference(s.reference), s.metrics.tolerance, s.metrics.xi_tolerance,
                                  s.tickPeriod());
  logger::watchLimits(metrics, s);

  // The lockstep order, tick by tick: plant sample -> controller -> actuator
  // -> physics. Every value passes through the same message structs as over
  // LCM, so both wirings compute with identical doubles.
  Eigen::MatrixXd tau = Eigen::MatrixXd::Zero(s.torqueStepsPerTick(), s.dof());  // row j: step j of a period
  const int64_t last_tick = s.lastTick();
  InProcessOutcome outcome;
  for (int64_t k = 0; k <= last_tick; ++k) {
    const double t = static_cast<double>(k) * s.tickPeriod();
    const plant::PlantSample sample = plant::measureTick(
        s, sensors, sim, k, t, tau.row(0).transpose(),
        k == 0 ? plant::TorqueInput{} : plant::TorqueInput{k - 1, lagrange::plant_truth_t::TORQUE_COMMANDED});
    record(transport::kPlantPosition, sample.position, sample.position.header.publish_utime);
    record(transport::kPlantTruth, sample.truth, sample.truth.header.publish_utime);
    const auto error =
        metrics.addSample(k, t, transport::toEigen(sample.truth.q), transport::toEigen(sample.truth.qdot));

    const double sample_time = sample.position.header.sim_time;
    if (sample.motor) {
      record(transport::kPlantMotor, *sample.motor, sample.motor->header.publish_utime);
      if (needs.motor_angles) assembly.motorSample(k, controller::motorSample(*sample.motor));
    }
    if (sample.rate) {
      record(transport::kPlantRate, *sample.rate, sample.rate->header.publish_utime);
      if (needs.joint_rates) assembly.rateSample(k, transport::toEigen(sample.rate->qdot));
    }
    // Every measurement of tick k is in: the assembly always answers here.
    const controller::AssembledInputs in =
        assembly.forTick(k, sample_time, transport::toEigen(sample.position.q)).value();
    const auto command = controller::commandMessage(ctl->step(in.inputs), k, sample_time, in.ticks);
    record(transport::kControlCommand, command, command.header.publish_utime);
    metrics.addChainErrors(k, command.header.sim_time, command.xi_error);
    const actuator::ActuatorOutput applied =
        act.step(transport::toEigen(command.u), s.tickPeriod(), s.torqueStepsPerTick());
    const auto state = actuator::actuatorMessage(applied, act.state(), command);
    if (needs.actuator_order > 0) assembly.chainState(k, act.state());
    record(transport::kActuatorState, state, state.header.publish_utime);
    tau = transport::toEigen(state.tau_applied);
    metrics.addTorque(k, tau);
    if (watch && !watch->keepGoing(k, error.value_or(std::nan("")), tau)) {
      outcome.status = "cut";
      break;
    }

    if (k % 100 == 0) {
      if (progress) {
        progress->update(t, error.value_or(std::nan("")));
        progress->tick();
      }
      if (stop_requested && stop_requested()) {
        outcome.exit_code = kExitInterrupted;
        break;
      }
    }
    if (k < last_tick) {
      try {
        sim.stepProfile(tau, s.substepsPerTick());
      } catch (const plant::PlantStopped& stopped) {  // keep what was recorded
        outcome.exit_code = kExitFailed;
        outcome.stop_message = stopped.what();
        break;
      }
    }
  }
  if (log) log->flush();
  if (outcome.status.empty())
    outcome.status = outcome.exit_code == kExitOk       ? "completed"
                     : outcome.exit_code == kExitFailed ? "diverged"
                                                        : "interrupted";
  outcome.tracking = metrics.summary();
  outcome.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return outcome;
}

int runInProcess(const config::Scenario& s, const controller::GainReport& gains, const std::string& out_dir,
                 ProgressDisplay& progress, bool (*stop_requested)()) {
  namespace fs = std::filesystem;
  const std::string log_path = (fs::path(out_dir) / "run.lcm").string();
  logger::EventLog log(log_path);
  const InProcessOutcome outcome = simulateInProcess(s, &log, &progress, stop_requested);
  if (!outcome.stop_message.empty())
    std::cerr << "lagrange run: " << util::terminalSafeLines(outcome.stop_message) << "\n";

  logger::RunFacts facts;
  facts.status = outcome.status;
  facts.log_path = log_path;
  facts.log_events = log.events();
  facts.wall_time = outcome.wall_time;
  log.close();  // throws naming run.lcm if its last bytes could not be written
  const auto summary = logger::makeSummary(s, outcome.tracking, gains, facts);
  util::writeOutputFile((fs::path(out_dir) / "summary.json").string(), summary.dump(2) + "\n");
  return outcome.exit_code;
}

}  // namespace lagrange::wiring
