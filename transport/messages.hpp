#pragma once
/// @file
/// Translation between LCM messages and the cores' Eigen types, and the
/// validation every received message passes before it reaches the math.

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/header_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/plant_rate_t.hpp"
#include "lagrange/plant_truth_t.hpp"
#include "lagrange/status_t.hpp"

namespace lagrange::transport {

/// Now on the run's clock [us since the Unix epoch]: monotonic, on the
/// wall clock by one offset per run and host (transport/run_clock.hpp).
int64_t nowUtime();

lagrange::header_t makeHeader(int64_t tick, double sim_time);

Eigen::VectorXd toEigen(const std::vector<double>& v);
/// Rows of equal length as a matrix (e.g. ACTUATOR_STATE's tau_applied).
Eigen::MatrixXd toEigen(const std::vector<std::vector<double>>& rows);
std::vector<double> toStd(const Eigen::VectorXd& v);

/// A plant's angle or rate past this (rad, m, rad/s, m/s) is refused: no arm
/// reaches it in a run, and the controllers' arithmetic would overflow.
inline constexpr double kPlausibleState = 1e9;

/// Each returns "" if the message is usable by a process that expects
/// `joints` joints, else the reason: joint count, array sizes, non-finite
/// numbers, negative tick; a plant's position, rate or truth also a state
/// past kPlausibleState.
std::string validate(const lagrange::plant_position_t& m, int joints);
std::string validate(const lagrange::plant_truth_t& m, int joints);
std::string validate(const lagrange::plant_rate_t& m, int joints);
/// with_rates: the scenario's motors have rate sensors (num_rates must be joints, else 0).
std::string validate(const lagrange::plant_motor_t& m, int joints, bool with_rates);
std::string validate(const lagrange::control_command_t& m, int joints);
/// torque_steps > 0 also demands that many rows of tau_applied (0: any count >= 1).
std::string validate(const lagrange::actuator_state_t& m, int joints, int torque_steps = 0);
std::string validate(const lagrange::status_t& m);

/// "" when a per-tick message's header keeps the run's clock, else why not:
/// its tick within [0, last_tick] (the scenario's ticks), and its sim_time
/// tick x period to a millionth of a period. The clock is the scenario's,
/// not a participant's: a plant stamping half the time, or ticks past the
/// run's end, must not stretch or pad what the logger measures.
std::string validateClock(const lagrange::header_t& h, long long last_tick, double period);

}  // namespace lagrange::transport
