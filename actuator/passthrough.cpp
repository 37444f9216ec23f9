#include "actuator/passthrough.hpp"

#include <stdexcept>
#include <string>

namespace lagrange::actuator {

PassthroughActuator::PassthroughActuator(int dof, std::optional<Eigen::VectorXd> saturation)
    : dof_(dof), saturation_(std::move(saturation)) {
  if (saturation_) {
    if (saturation_->size() != dof)
      throw std::invalid_argument("actuator: saturation has " + std::to_string(saturation_->size()) +
                                  " entries, expected " + std::to_string(dof));
    if (!(saturation_->array() > 0.0).all())
      throw std::invalid_argument("actuator: saturation limits must be positive");
  }
}

ActuatorOutput PassthroughActuator::step(const Eigen::VectorXd& u) const {
  if (u.size() != dof_)
    throw std::invalid_argument("actuator: command has " + std::to_string(u.size()) + " entries, expected " +
                                std::to_string(dof_));
  ActuatorOutput out;
  out.tau = u;
  out.saturated = Eigen::Array<bool, Eigen::Dynamic, 1>::Constant(dof_, false);
  if (saturation_) {
    out.tau = u.cwiseMax(-*saturation_).cwiseMin(*saturation_);
    out.saturated = out.tau.array() != u.array();
  }
  return out;
}

}  // namespace lagrange::actuator
