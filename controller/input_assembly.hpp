#pragma once
/// @file
/// What the controller process feeds its controller each tick, from the
/// measurements as they arrive (the protocol rule, out of the process main):
///  - the actuator chain's state: ACTUATOR_STATE of tick k carries xi at
///    t_{k+1}, so it belongs to position k+1 (tick 0: the configured xi(0));
///  - the motor sample of flexible joints: PLANT_MOTOR of tick k, rows q2 and,
///    with a rate sensor, q2', belongs to position k;
///  - the velocity sensor's reading: PLANT_RATE of tick k belongs to position k.
/// Lockstep answers position k only with the measurements of tick k (none yet:
/// no answer; the plant re-sends position k and it is answered then). Realtime
/// uses the newest chain state and motor sample (latest-value semantics), the
/// configured initial state before the first arrives; but a rate only of the
/// position's own tick (the plant sends it first): a position whose rate is
/// missing is not answered, so a command never pairs q and q' of different
/// instants, and the command's position tick names its rate. Pure: no I/O.

#include <Eigen/Dense>
#include <cstdint>
#include <optional>

#include "controller/chain_state_buffer.hpp"
#include "controller/controller.hpp"

namespace lagrange::controller {

/// The ticks of the measurements a command was computed from, -1 where none
/// was used: CONTROL_COMMAND's input ticks.
struct InputTicks {
  int64_t actuator = -1;  ///< the ACTUATOR_STATE whose xi was used
  int64_t motor = -1;     ///< the PLANT_MOTOR whose sample was used
};

struct AssembledInputs {
  ControllerInputs inputs;
  InputTicks ticks;
};

class InputAssembly {
 public:
  /// @param initial_chain_state xi(0), (order x n); used when needs.actuator_order > 0.
  /// @param initial_motor realtime's motor sample before the first PLANT_MOTOR
  ///        (rows q2 [, q2']); used when needs.motor_angles.
  /// @throws std::invalid_argument when needs.motor_rates and initial_motor has no rate row.
  InputAssembly(Needs needs, const Eigen::MatrixXd& initial_chain_state,
                const Eigen::MatrixXd& initial_motor);

  /// ACTUATOR_STATE of tick `actuator_tick` with chain state xi.
  void chainState(int64_t actuator_tick, const Eigen::MatrixXd& xi);
  /// PLANT_MOTOR of tick `tick`, rows q2 [, q2'].
  /// @throws std::invalid_argument when needs.motor_rates and the sample has no rate row.
  void motorSample(int64_t tick, const Eigen::MatrixXd& sample);

  /// PLANT_RATE of tick `tick`: the measured joint rates.
  void rateSample(int64_t tick, const Eigen::VectorXd& qdot);

  /// Lockstep: the inputs of position `tick` (time t, angles q), or nothing
  /// while a measurement of that tick the controller needs is missing.
  std::optional<AssembledInputs> forTick(int64_t tick, double t, const Eigen::VectorXd& q);
  /// Realtime: the inputs of position `tick` with the newest chain state and
  /// motor sample; nothing when the controller needs rates and that tick's
  /// has not arrived.
  std::optional<AssembledInputs> newest(int64_t tick, double t, const Eigen::VectorXd& q);

 private:
  AssembledInputs assemble(double t, const Eigen::VectorXd& q, const Eigen::MatrixXd* xi,
                           const Eigen::MatrixXd* motor, const Eigen::MatrixXd* rate, InputTicks ticks) const;
  void checkMotor(const Eigen::MatrixXd& sample, const char* what) const;

  Needs needs_;
  ChainStateBuffer chain_by_tick_;
  ChainStateBuffer motor_by_tick_;
  ChainStateBuffer rate_by_tick_;  ///< one-column matrices: q'
  Eigen::MatrixXd newest_chain_;
  int64_t newest_chain_position_ = 0;  ///< the position tick the newest xi belongs to
  Eigen::MatrixXd newest_motor_;
  int64_t newest_motor_tick_ = -1;
};

}  // namespace lagrange::controller
