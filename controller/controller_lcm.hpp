#pragma once
/// @file
/// The controller's messages: CONTROL_COMMAND from a controller's output, and
/// PLANT_MOTOR as its input. One place, used by the controller process, the
/// in-process runner and the benchmarks alike.

#include <cstdint>

#include "controller/input_assembly.hpp"
#include "controller/theorem1.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "transport/lcm_node.hpp"

namespace lagrange::controller {

/// What the measurements of a run look like, for checking them on arrival.
struct MeasurementShape {
  int joints = 0;
  int torque_steps_per_tick = 0;  ///< of ACTUATOR_STATE (actuator.rate)
  bool motor_rates = false;       ///< PLANT_MOTOR carries q2' (a motor rate sensor)
};

/// Subscribes NODE to the measurements besides q that a controller declared
/// (NEEDS: ACTUATOR_STATE of its order, PLANT_MOTOR, PLANT_RATE), each checked
/// against SHAPE and handed to ASSEMBLY with its tick. ASSEMBLY must outlive
/// the node's handling.
void subscribeDeclaredInputs(transport::LcmNode& node, const Needs& needs, const MeasurementShape& shape,
                             InputAssembly& assembly);

lagrange::control_command_t commandMessage(const Theorem1Output& out, int64_t position_tick, double sim_time,
                                           InputTicks inputs = {});

/// PLANT_MOTOR as InputAssembly::motorSample takes it: rows q2 and, when the
/// message carries rates (a rate sensor), q2'.
Eigen::MatrixXd motorSample(const lagrange::plant_motor_t& m);

/// A diagnostic as CONTROL_COMMAND carries it: the message's fields are fixed,
/// so one the controller does not have (empty) goes out as `joints` zeros.
/// Replay compares a recorded command with what this makes of the replayed one.
Eigen::VectorXd asPublished(const Eigen::VectorXd& diagnostic, Eigen::Index joints);

}  // namespace lagrange::controller
