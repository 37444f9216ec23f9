#pragma once
/// @file
/// What a real arm has at its joints and the lossless model (eq. 10) has not:
/// viscous damping, Coulomb friction and hard stops. Inside plant/ only (this
/// header includes ODE).
///
/// Damping and friction are ODE angular motors (dJointCreateAMotor, one axis:
/// the hinge's), one each per joint, aiming at zero relative rate:
///  - damping D: no force limit and a constraint-force mixing of 1/D, which
///    makes the motor's torque -D q' with q' the rate at the end of the step
///    (dWorldStep solves J v' = -cfm lambda): implicit, so stable for any D
///    and step, where an explicit -D q' would blow up once D h / I > 2;
///  - Coulomb friction F: force limit F, the world's tiny mixing: the torque that stops the
///    joint if at most F does (stiction), else F against the motion -- what
///    an LCP solves well, with no sign() discontinuity to chatter on.
/// Each motor reports the torque it applied (dJointSetFeedback), so the
/// energy the joints dissipated is the sum of -tau q' h over the steps, in
/// ODE's own terms.
///
/// Hard stops are the hinge's own (dParamLoStop, dParamHiStop; inelastic).
/// ODE measures a hinge's angle from where it was built and only within
/// (-pi, pi], so each step the stops are placed relative to the hinge's
/// current wrap (q - hinge angle); a stop outside (-pi, pi] in that wrap
/// waits until the joint turns into the wrap where it lies.

#include <ode/ode.h>

#include <Eigen/Dense>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lagrange::plant {

/// Per-joint losses; an empty vector: none.
struct JointLosses {
  Eigen::VectorXd damping;   ///< D_i >= 0 [N m s/rad]: a torque -D_i q'_i
  Eigen::VectorXd friction;  ///< F_i >= 0 [N m]: at most F_i against the joint's motion
  bool any() const { return damping.size() > 0 || friction.size() > 0; }
};

/// Per-joint hard stops [rad]; -inf / +inf: none on that side; empty: none.
struct JointStops {
  Eigen::VectorXd lower, upper;
  bool any() const { return lower.size() > 0; }
};

class JointEffects {
 public:
  /// @param hinges the joints, each attached (moving body, parent or world)
  /// @param q the joints' continuous angles now (for the stops' wrap)
  /// @throws std::invalid_argument on a size mismatch or a negative, non-finite value
  /// @param label names the joints in errors ("joint", "rotor")
  JointEffects(dWorldID world, const std::vector<dJointID>& hinges, const JointLosses& losses,
               const JointStops& stops, const Eigen::VectorXd& q, const std::string& label = "joint");
  ~JointEffects();
  JointEffects(const JointEffects&) = delete;
  JointEffects& operator=(const JointEffects&) = delete;

  /// Before a step: places the stops for the joints' continuous angles q.
  void beforeStep(const Eigen::VectorXd& q);
  /// After a step of h seconds: adds what the damping and friction took.
  void afterStep(const Eigen::VectorXd& rates, double h);
  /// Energy taken by the damping and the friction since the start [J].
  double dissipated() const { return dissipated_; }

 private:
  struct Motor {
    int joint;
    dJointID amotor;
    std::unique_ptr<dJointFeedback> feedback;
  };
  Motor motorOn(dWorldID world, int joint, double fmax, std::optional<double> cfm);

  std::vector<dJointID> hinges_;
  std::vector<Motor> motors_;
  JointStops stops_;
  double dissipated_ = 0.0;
};

}  // namespace lagrange::plant
