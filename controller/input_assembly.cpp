#include "controller/input_assembly.hpp"

#include <stdexcept>
#include <string>

namespace lagrange::controller {

InputAssembly::InputAssembly(Needs needs, const Eigen::MatrixXd& initial_chain_state,
                             const Eigen::MatrixXd& initial_motor)
    : needs_(needs),
      chain_by_tick_(initial_chain_state),
      newest_chain_(initial_chain_state),
      newest_motor_(initial_motor) {
  if (needs_.motor_angles) checkMotor(initial_motor, "the initial motor state");
}

void InputAssembly::checkMotor(const Eigen::MatrixXd& sample, const char* what) const {
  const Eigen::Index rows = needs_.motor_rates ? 2 : 1;
  if (sample.rows() < rows)
    throw std::invalid_argument(std::string("controller inputs: ") + what + " has " +
                                std::to_string(sample.rows()) + " rows, expected " + std::to_string(rows) +
                                (needs_.motor_rates ? " (q2 and the measured q2')" : " (q2)"));
}

void InputAssembly::chainState(int64_t actuator_tick, const Eigen::MatrixXd& xi) {
  const int64_t position = actuator_tick + 1;
  chain_by_tick_.put(position, xi);
  if (position <= newest_chain_position_) return;  // not newer than what we have
  newest_chain_ = xi;
  newest_chain_position_ = position;
}

void InputAssembly::motorSample(int64_t tick, const Eigen::MatrixXd& sample) {
  checkMotor(sample, "a motor sample");
  motor_by_tick_.put(tick, sample);
  if (tick > newest_motor_tick_) newest_motor_ = sample, newest_motor_tick_ = tick;
}

void InputAssembly::rateSample(int64_t tick, const Eigen::VectorXd& qdot) { rate_by_tick_.put(tick, qdot); }

std::optional<AssembledInputs> InputAssembly::forTick(int64_t tick, double t, const Eigen::VectorXd& q) {
  std::optional<Eigen::MatrixXd> motor, xi, rate;
  if (needs_.motor_angles && !(motor = motor_by_tick_.take(tick))) return std::nullopt;
  if (needs_.actuator_order > 0 && !(xi = chain_by_tick_.take(tick))) return std::nullopt;
  if (needs_.joint_rates && !(rate = rate_by_tick_.take(tick))) return std::nullopt;
  return assemble(t, q, xi ? &*xi : nullptr, motor ? &*motor : nullptr, rate ? &*rate : nullptr,
                  {needs_.actuator_order > 0 ? tick - 1 : -1, needs_.motor_angles ? tick : -1});
}

std::optional<AssembledInputs> InputAssembly::newest(int64_t tick, double t, const Eigen::VectorXd& q) {
  std::optional<Eigen::MatrixXd> rate;
  if (needs_.joint_rates && !(rate = rate_by_tick_.take(tick))) return std::nullopt;
  return assemble(t, q, &newest_chain_, &newest_motor_, rate ? &*rate : nullptr,
                  {needs_.actuator_order > 0 ? newest_chain_position_ - 1 : -1,
                   needs_.motor_angles ? newest_motor_tick_ : -1});
}

AssembledInputs InputAssembly::assemble(double t, const Eigen::VectorXd& q, const Eigen::MatrixXd* xi,
                                        const Eigen::MatrixXd* motor, const Eigen::MatrixXd* rate,
                                        InputTicks ticks) const {
  AssembledInputs out;
  out.inputs.t = t;
  out.inputs.q = q;
  if (needs_.joint_rates) out.inputs.qdot = rate->col(0);
  if (needs_.actuator_order > 0) out.inputs.xi = *xi;
  if (needs_.motor_angles) out.inputs.motor_q = motor->row(0).transpose();
  if (needs_.motor_angles && needs_.motor_rates) out.inputs.motor_qdot = motor->row(1).transpose();
  out.ticks = ticks;
  return out;
}

}  // namespace lagrange::controller
