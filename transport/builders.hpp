#pragma once
/// @file
/// Building the messages the cores' outputs become. One place, used by the
/// process mains and by the in-process runner alike, so both wirings publish
/// exactly the same numbers.

#include <Eigen/Dense>
#include <optional>

#include "actuator/integrator_chain.hpp"
#include "config/scenario.hpp"
#include "controller/theorem1.hpp"
#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/plant_truth_t.hpp"
#include "lagrange/scenario_t.hpp"

namespace lagrange::transport {

/// What the plant publishes for one tick.
struct PlantSample {
  lagrange::plant_position_t position;
  lagrange::plant_truth_t truth;
};

/// SCENARIO: the resolved scenario as YAML (config::toYaml).
lagrange::scenario_t scenarioMessage(const config::Scenario& s);

/// Which torque the plant applied over a period, and why (plant_truth_t).
struct TorqueInput {
  int64_t actuator_tick = -1;
  int8_t source = lagrange::plant_truth_t::TORQUE_ZERO;
};

/// tau_applied: the torque applied over the period that ended at this tick, chosen as `input` says.
PlantSample plantSample(int64_t tick, double sim_time, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                        const Eigen::VectorXd& tau_applied, double kinetic_energy, double potential_energy,
                        TorqueInput input);

/// PLANT_MOTOR of a flexible-joint arm; motor_qdot is sent only when with_rates.
lagrange::plant_motor_t motorMessage(int64_t tick, double sim_time, const Eigen::VectorXd& motor_q,
                                     const Eigen::VectorXd& motor_qdot, bool with_rates);

/// q2' of a PLANT_MOTOR message, if it carries rates.
std::optional<Eigen::VectorXd> motorRates(const lagrange::plant_motor_t& m);

/// The ticks of the inputs a command was computed from (-1: a configured initial state, or none).
struct InputTicks {
  int64_t actuator = -1;
  int64_t motor = -1;
};

lagrange::control_command_t commandMessage(const controller::Theorem1Output& out, int64_t position_tick,
                                           double sim_time, InputTicks inputs = {});

/// xi_next: the chain state at the end of the period (m x n), what the
/// controller measures at the next tick.
lagrange::actuator_state_t actuatorMessage(const actuator::ActuatorOutput& out,
                                           const Eigen::MatrixXd& xi_next,
                                           const lagrange::control_command_t& command);

}  // namespace lagrange::transport
