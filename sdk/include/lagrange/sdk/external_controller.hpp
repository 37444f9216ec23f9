#pragma once
/// @file
/// lagrange's C++ SDK: a controller of your own in a lagrange run
/// (controller.type: external), built outside this tree against the
/// installed package:
///
///     find_package(lagrange REQUIRED)
///     target_link_libraries(my_controller PRIVATE lagrange::sdk)
///
/// You write the law; run() keeps the contract of
/// docs/external_programs.md: the run's LCM URL, id, key and joint count
/// from the environment, the MAC on every datagram (checked before anything
/// is decoded), the header (run id, publisher, pid, per-channel seq, the
/// run's clock, checksum), which positions to accept, lockstep's re-sent
/// ticks (answered with the same command; the law is never stepped twice on
/// one sample), the STATUS handshake, realtime. The message types are
/// lcm-gen's (<lagrange/plant_position_t.hpp>, ...), installed beside it.

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace lagrange::sdk {

/// What the law returns for one sample: u [N m], one per joint, and
/// optionally its diagnostics (one per joint each, or empty: zeros), which
/// the log, the CSV and HDF5 exports, the plots and replay carry.
struct Command {
  std::vector<double> u;
  std::vector<double> q_desired, q_error, theta, filter_state;
};

/// The law: the sample's sim time t [s] and joint angles q [rad] -> the command.
using Step = std::function<Command(double t, const std::vector<double>& q)>;

/// The environment or the law broke the contract (the message says how).
class ContractError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Serves `step` as the run's controller until the plant finishes; calls
/// `reset` (when given) once before the first sample. Returns 0 then; on a
/// ContractError or an LCM failure prints it, prefixed with `program`, to
/// stderr and returns 1: `return lagrange::sdk::run(step);` from main.
int run(const Step& step, const std::function<void()>& reset = {}, const std::string& program = "controller");

}  // namespace lagrange::sdk
