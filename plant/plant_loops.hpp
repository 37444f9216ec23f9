#pragma once
/// @file
/// The two ways the plant process drives a run (DESIGN section 4).
///
/// Lockstep: for tick k = 0..N publish the sample of tick k, wait for the
/// ACTUATOR_STATE of tick k (re-sending after lockstep.retransmit_timeout),
/// then apply its torque for one period; never more than
/// lockstep.logger_window ticks ahead of the logger. No wait is endless:
/// past lockstep.stall_timeout (at the start, startupTimeout()) the plant
/// throws PlantStalled naming whom it waited for and what it saw.
///
/// Realtime: a fixed-rate loop on the monotonic clock. At each deadline
/// publish the sample of tick k, choose the torque for [t_k, t_k+1) from the
/// newest ACTUATOR_STATE (latest-value semantics; typically the answer to
/// tick k-1), apply the stale-torque policy when it is too old, and step the
/// physics one period. It starts once every other process has reported,
/// within the same deadline.

#include "config/scenario.hpp"
#include "plant/plant_sim.hpp"
#include "runtime/process.hpp"
#include "transport/lcm_node.hpp"

namespace lagrange::plant {

/// How long the start may take -- every process up and reporting, the first
/// tick answered -- before the run is stalled: three times
/// lockstep.stall_timeout (30 s by default), since processes load, check
/// their gains (about a second of CPU on a URDF arm) or start a JVM first.
inline double startupTimeout(const config::Scenario& s) { return 3.0 * s.lockstep.stall_timeout; }

/// Both return the exit code; they publish the final STATUS themselves.
int runLockstep(const config::Scenario& s, transport::LcmNode& node, PlantSim& sim,
                runtime::StatusReporter& status);
int runRealtime(const config::Scenario& s, transport::LcmNode& node, PlantSim& sim,
                runtime::StatusReporter& status);

}  // namespace lagrange::plant
