#pragma once
/// @file
/// The two ways the plant process drives a run (DESIGN section 4).
///
/// Lockstep: for tick k = 0..N publish the sample of tick k, wait for the
/// ACTUATOR_STATE of tick k (re-sending after lockstep.retransmit_timeout),
/// then apply its torque for one period; never more than
/// lockstep.logger_window ticks ahead of the logger.
///
/// Realtime: a fixed-rate loop on the monotonic clock. At each deadline
/// publish the sample of tick k, choose the torque for [t_k, t_k+1) from the
/// newest ACTUATOR_STATE (latest-value semantics; typically the answer to
/// tick k-1), apply the stale-torque policy when it is too old, and step the
/// physics one period.

#include "config/scenario.hpp"
#include "plant/plant_sim.hpp"
#include "runtime/process.hpp"
#include "transport/lcm_node.hpp"

namespace lagrange::plant {

/// Both return the exit code; they publish the final STATUS themselves.
int runLockstep(const config::Scenario& s, transport::LcmNode& node, PlantSim& sim,
                runtime::StatusReporter& status, double startup_timeout);
int runRealtime(const config::Scenario& s, transport::LcmNode& node, PlantSim& sim,
                runtime::StatusReporter& status, double startup_timeout);

}  // namespace lagrange::plant
