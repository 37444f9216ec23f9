#pragma once
/// @file
/// The plant's messages from its state (PLANT_POSITION, PLANT_TRUTH,
/// PLANT_MOTOR) and back. One place, used by the plant process, the
/// in-process runner and replay alike, so every wiring publishes exactly the
/// same numbers.

#include <Eigen/Dense>
#include <cstdint>
#include <optional>

#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/plant_rate_t.hpp"
#include "lagrange/plant_truth_t.hpp"

namespace lagrange::plant {

/// What the plant publishes for one tick.
struct PlantSample {
  lagrange::plant_position_t position;
  lagrange::plant_truth_t truth;
  std::optional<lagrange::plant_motor_t> motor;  ///< flexible joints only
  std::optional<lagrange::plant_rate_t> rate;    ///< with a velocity sensor only
};

/// Which torque the plant applied over a period, and why (plant_truth_t).
struct TorqueInput {
  int64_t actuator_tick = -1;
  int8_t source = lagrange::plant_truth_t::TORQUE_ZERO;
};

/// tau_applied: the torque applied over the period that ended at this tick, chosen as `input` says.
/// q_measured: what the joint-angle sensor read (PLANT_POSITION; plant/joint_sensor.hpp);
/// q, the true angles, goes to PLANT_TRUTH.
PlantSample plantSample(int64_t tick, double sim_time, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                        const Eigen::VectorXd& tau_applied, double kinetic_energy, double potential_energy,
                        TorqueInput input, const Eigen::VectorXd& q_measured);

/// PLANT_MOTOR of a flexible-joint arm; motor_qdot is sent only when with_rates.
lagrange::plant_motor_t motorMessage(int64_t tick, double sim_time, const Eigen::VectorXd& motor_q,
                                     const Eigen::VectorXd& motor_qdot, bool with_rates);

/// PLANT_RATE: the velocity sensor's reading.
lagrange::plant_rate_t rateMessage(int64_t tick, double sim_time, const Eigen::VectorXd& qdot_measured);

/// q2' of a PLANT_MOTOR message, if it carries rates.
std::optional<Eigen::VectorXd> motorRates(const lagrange::plant_motor_t& m);

}  // namespace lagrange::plant
