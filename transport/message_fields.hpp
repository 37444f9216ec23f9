#pragma once
/// @file
/// The recorded fields of each per-tick message type, in one place, for the
/// readers that turn a log into tables: the CSV export (`lagrange report`)
/// and the HDF5 export (`lagrange export`). fields(visitor, message) calls
/// visitor.add(name, value, unit) for each field after the header, with value
/// a double, a per-joint std::vector<double>, or rows of them (chain stages,
/// torque steps). Units are lcmtypes/*.lcm's. The array sizes (num_joints,
/// order, torque_steps, chain_order, num_rates) are not fields here: they are
/// the shapes of the others.

#include <string>
#include <vector>

#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/plant_rate_t.hpp"
#include "lagrange/plant_truth_t.hpp"

namespace lagrange::transport {

/// The unit of a commanded input u: a torque for a rigid arm, its m-th
/// derivative behind an m-th order actuator chain (docs/external_programs.md).
inline constexpr const char* kInputUnit = "N m (rigid arm; N m / s^m behind an actuator chain of order m)";

template <class V>
void fields(V& v, const lagrange::plant_truth_t& m) {
  v.add("q", m.q, "rad"), v.add("qdot", m.qdot, "rad/s"), v.add("tau_applied", m.tau_applied, "N m");
  v.add("kinetic_energy", m.kinetic_energy, "J"), v.add("potential_energy", m.potential_energy, "J");
  v.add("total_energy", m.total_energy, "J");
  v.add("input_actuator_tick", static_cast<double>(m.input_actuator_tick), "tick");
  v.add("torque_source", m.torque_source, "0 commanded, 1 held, 2 zero");
}
template <class V>
void fields(V& v, const lagrange::plant_position_t& m) {
  v.add("q", m.q, "rad");
}
template <class V>
void fields(V& v, const lagrange::plant_rate_t& m) {
  v.add("qdot", m.qdot, "rad/s");
}
template <class V>
void fields(V& v, const lagrange::plant_motor_t& m) {
  v.add("q", m.q, "rad"), v.add("qdot", m.qdot, "rad/s");
}
template <class V>
void fields(V& v, const lagrange::control_command_t& m) {
  v.add("input_position_tick", static_cast<double>(m.input_position_tick), "tick");
  v.add("input_actuator_tick", static_cast<double>(m.input_actuator_tick), "tick (-1: none)");
  v.add("input_motor_tick", static_cast<double>(m.input_motor_tick), "tick (-1: none)");
  v.add("u", m.u, kInputUnit), v.add("q_desired", m.q_desired, "rad"), v.add("q_error", m.q_error, "rad");
  v.add("theta", m.theta, "rad/s (when b = a)"), v.add("filter_state", m.filter_state, "rad/s (when b = a)");
  v.add("xi_error", m.xi_error, "N m / s^(k-1) for stage k");
}
template <class V>
void fields(V& v, const lagrange::actuator_state_t& m) {
  v.add("input_command_tick", static_cast<double>(m.input_command_tick), "tick (-1: none)");
  v.add("u_commanded", m.u_commanded, kInputUnit), v.add("tau_applied", m.tau_applied, "N m");
  v.add("saturated", std::vector<double>(m.saturated.begin(), m.saturated.end()), "1 where clipped, else 0");
  v.add("xi", m.xi, "N m / s^(k-1) for stage k");
}

}  // namespace lagrange::transport
