#pragma once
/// @file
/// The controller seam: every controller -- the paper's and any other --
/// is a Controller. The processes and the in-process runner build one from
/// the scenario through the registry (controller/registry.hpp), feed it the
/// measurements it declares, and publish its command; none of them knows
/// which controller it runs. Pure: no I/O, no clock.

#include <Eigen/Dense>
#include <optional>

#include "controller/theorem1.hpp"

namespace lagrange::controller {

/// The command of one step. u is what is applied (a torque, or the input of
/// the actuator chain); the others are diagnostics, carried by
/// CONTROL_COMMAND and so picked up by the log, the CSV export and the
/// plots without per-controller code. A controller fills the ones it has
/// and leaves the others empty (zero length); CONTROL_COMMAND's fields are
/// fixed, so an empty diagnostic is sent as zeros (controller_lcm.cpp).
/// Diagnostics beyond these five need a message of their own (not yet).
using ControllerCommand = Theorem1Output;

/// The measurements a controller needs besides the link angles q, which
/// every controller receives. The processes subscribe to exactly these.
struct Needs {
  /// Order m of the actuator integrator chain whose state xi (m x n) it reads; 0: none.
  int actuator_order = 0;
  bool motor_angles = false;  ///< q2 of a flexible-joint arm (PLANT_MOTOR)
  bool motor_rates = false;   ///< q2' too (PLANT_MOTOR with rates)
  /// q' from a velocity sensor (PLANT_RATE): a scenario without one
  /// (sensors.velocity) is refused before anything starts.
  bool joint_rates = false;
};

/// What a controller sees at one sample. Fields it did not declare in
/// Needs are empty.
struct ControllerInputs {
  double t = 0.0;                             ///< the sample's time [s]
  Eigen::VectorXd q;                          ///< link angles [rad]
  Eigen::VectorXd qdot;                       ///< measured joint rates [rad/s] (Needs::joint_rates)
  Eigen::MatrixXd xi;                         ///< actuator chain state, m x n (Needs::actuator_order = m)
  Eigen::VectorXd motor_q;                    ///< q2 [rad] (Needs::motor_angles)
  std::optional<Eigen::VectorXd> motor_qdot;  ///< q2' [rad/s] (Needs::motor_rates)
};

class Controller {
 public:
  virtual ~Controller() = default;
  virtual Needs needs() const = 0;
  /// The command at in.t. Times increase from call to call.
  virtual ControllerCommand step(const ControllerInputs& in) = 0;
  /// Back to the state it was built in (filters at their configured start).
  virtual void reset() = 0;
};

}  // namespace lagrange::controller
