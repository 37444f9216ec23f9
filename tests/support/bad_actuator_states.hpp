#pragma once
// Three ACTUATOR_STATEs a run of two joints behind an order-1 chain (one
// torque step a tick) must refuse as invalid, each for its own reason:
// chain order 2, three joints, two torque steps. Shared by the node-level
// unit test (tests/unit/input_validation_test.cpp) and the run under such
// traffic (tests/integration/bad_input_test.cpp).
#include "lagrange/actuator_state_t.hpp"
#include "transport/messages.hpp"

namespace lagrange::testing {

struct BadActuatorStates {
  lagrange::actuator_state_t wrong_order, wrong_size, wrong_steps;
};

inline BadActuatorStates badActuatorStates(int64_t tick, double sim_time) {
  BadActuatorStates bad;
  lagrange::actuator_state_t& o = bad.wrong_order;
  o.header = transport::makeHeader(tick, sim_time);
  o.input_command_tick = tick;
  o.num_joints = 2;
  o.order = 2;
  o.u_commanded = {0.0, 0.0};
  o.torque_steps = 1;
  o.tau_applied = {{0.0, 0.0}};
  o.saturated = {0, 0};
  o.xi = {{1.0, 1.0}, {1.0, 1.0}};
  bad.wrong_size = o;
  bad.wrong_size.order = 1;
  bad.wrong_size.num_joints = 3;
  bad.wrong_size.u_commanded = {0.0, 0.0, 0.0};
  bad.wrong_size.tau_applied = {{0.0, 0.0, 0.0}};
  bad.wrong_size.saturated = {0, 0, 0};
  bad.wrong_size.xi = {{1.0, 1.0, 1.0}};
  bad.wrong_steps = o;
  bad.wrong_steps.order = 1;
  bad.wrong_steps.xi = {{1.0, 1.0}};
  bad.wrong_steps.torque_steps = 2;
  bad.wrong_steps.tau_applied = {{0.0, 0.0}, {0.0, 0.0}};
  return bad;
}

}  // namespace lagrange::testing
