#include "plant/plant_sim.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace lagrange::plant {

PlantSim::PlantSim(const ArmBuilder& arm, const PlantState& initial, double physics_step,
                   std::optional<model::FlexibleParams> flexible, std::optional<double> max_rate,
                   const JointPhysics& joints, const EngineChoice& engine)
    : dof_(arm.dof), physics_step_(physics_step), max_rate_(max_rate) {
  if (max_rate_ && !(*max_rate_ > 0.0))
    throw std::invalid_argument("plant: max_rate must be positive, got " + std::to_string(*max_rate_));
  if (flexible) {
    model::validateFlexible(*flexible, dof_);
    if (initial.motor_q.size() != dof_ || initial.motor_qdot.size() != dof_)
      throw std::invalid_argument("plant: flexible joints need " + std::to_string(dof_) +
                                  " initial motor angles and rates");
    if (!initial.motor_q.allFinite() || !initial.motor_qdot.allFinite())
      throw std::invalid_argument("plant: initial motor state must be finite");
  }
  if (!(physics_step > 0.0) || !std::isfinite(physics_step))
    throw std::invalid_argument("plant: physics_step must be positive and finite");
  if (initial.q.size() != dof_ || initial.qdot.size() != dof_)
    throw std::invalid_argument("plant: initial state must have " + std::to_string(dof_) +
                                " joint angles and rates");
  if (!initial.q.allFinite() || !initial.qdot.allFinite())
    throw std::invalid_argument("plant: initial state must be finite");
  checkJointPhysics(joints, dof_, flexible.has_value());
  engine_ = makePhysicsEngine({arm, initial, physics_step, std::move(flexible), joints, engine});
}

PlantSim::~PlantSim() = default;

void PlantSim::checkBounded() const {
  // See the class comment: only a failing simulation or the user's limit stops a run.
  const double worst = engine_->fastestBodyRate();
  // Built only when the run stops: formatting a double on every call was a
  // per-step cost (printf's float formatting showed in the plant's profile).
  const auto at = [this] { return "at t = " + std::to_string(time_) + " s"; };
  if (const std::string why = engine_->unsound(); !why.empty())
    throw PlantStopped("plant: the simulation diverged " + at() + ": " + why);
  const double resolvable = kMaxTurnPerStep / physics_step_;
  if (!(worst < resolvable))
    throw PlantStopped(
        "plant: the simulation diverged " + at() + ": a body turns at " + std::to_string(worst) +
        " rad/s, more than pi/2 per physics step (limit " + std::to_string(resolvable) +
        " rad/s at plant.physics_step = " + std::to_string(physics_step_) + " s), which " + engine_->name() +
        " cannot integrate; the closed loop is unstable, or needs a smaller physics_step");
  if (max_rate_ && !(worst <= *max_rate_))
    throw PlantStopped("plant: stopped " + at() + ": a body turns at " + std::to_string(worst) +
                       " rad/s, above plant.max_rate = " + std::to_string(*max_rate_) + " rad/s");
}

void PlantSim::step(const Eigen::VectorXd& tau, int substeps) {
  if (tau.size() != dof_)
    throw std::invalid_argument("plant: torque has " + std::to_string(tau.size()) + " entries, expected " +
                                std::to_string(dof_));
  for (int s = 0; s < substeps; ++s) {
    engine_->step(tau);
    time_ += physics_step_;
    checkBounded();
  }
}

void PlantSim::stepProfile(const Eigen::MatrixXd& tau, int substeps) {
  const int parts = static_cast<int>(tau.rows());
  if (parts < 1 || substeps % parts != 0)
    throw std::invalid_argument("plant: " + std::to_string(parts) + " torque steps do not divide " +
                                std::to_string(substeps) + " physics steps");
  for (int s = 0; s < parts; ++s) step(Eigen::VectorXd(tau.row(s).transpose()), substeps / parts);
}

PlantState PlantSim::state() const { return engine_->state(); }
PlantEnergy PlantSim::energy() const { return engine_->energy(); }
double PlantSim::dissipated() const { return engine_->dissipated(); }
double PlantSim::jointSeparation() const { return engine_->jointSeparation(); }
std::string PlantSim::engineName() const { return engine_->name(); }

}  // namespace lagrange::plant
