#pragma once
/// @file
/// The sampled-data verdict by simulation (controller::SampledSimulation):
/// is the loop as configured -- its rate, sensors, actuator chain and
/// saturation, the plant's payload, model error, damping, friction and stops
/// -- as good as the same loop at a rate that stands for continuous time?
///
/// From the scenario's initial state and kSeededStates more of the same
/// position-error norm (directions drawn from a fixed seed), two in-process
/// simulations each, over the scenario's duration (wiring::simulateInProcess,
/// no log):
///  - sampled: the scenario as configured. The realtime wiring's one period
///    of delay is simulated as one more sample of joint-angle sensor delay
///    (the same lag; the reference a period apart);
///  - fine: the same arm, plant, controller gains and actuator saturation at
///    the fine rate F, with exact sensors and no delay, the actuator updating
///    once a period, the physics step the scenario's or less (so that it
///    divides 1/F).
/// F starts at 8 x the configured rate and is confirmed by refinement: the
/// initial state's fine loop at 2F must agree with it (convergence times
/// within 5 % and two periods, or, where neither converges, steady-state
/// errors within 5 %); else F doubles, up to 64 x.
///
/// Each start's word (controller::SampledSimulation::verdict lists them):
/// ADEQUATE when the sampled loop converges by kSlack x the fine loop's time
/// plus two periods; OFFSET when neither loop reaches the tolerance and the
/// sampled loop's steady-state error (RMS over the last second) is within
/// kSlack x the fine one's plus a quarter of the tolerance (not sampling's
/// doing; the likely cause named from the plant's keys); DIVERGES when the
/// sampled simulation is stopped or ends farther off than it started. Where
/// sampling costs something (slower, or a larger error, than the fine loop),
/// one more simulation decides between SLOW and UNSTABLE: the sampled loop
/// without torque limits from 10 x the tolerance off the reference. If it
/// grows, the loop is unstable about the reference (and, with
/// actuator.saturation and the configured loop bounded, held off only by
/// saturation); else it is slow. The overall verdict is the worst start's. A
/// controller that does not run in process (external) is "not assessed".

#include <optional>
#include <string>

#include "config/scenario.hpp"
#include "controller/sampled_data.hpp"
#include "util/error.hpp"

namespace lagrange::wiring {

inline constexpr int kSeededStates = 2;

/// What one loop did: "completed", or "diverged" (the simulation was
/// stopped); its convergence time; its RMS error over the last second [rad].
struct LoopOutcome {
  std::string status;
  std::optional<double> time;
  double error = 0.0;
};

/// The verdict for the scenario at its plant.publish_rate. Runs the
/// simulations in process on up to `jobs` threads at a time, the calling
/// thread one of them (0: one per core; 1: all on the calling thread). The
/// verdict is the same whatever `jobs` (each simulation is its scenario's
/// alone, and the results are read in a fixed order); safe to call from
/// several threads at once (lagrange tune's workers, with jobs = 1).
/// `initial_run`: the scenario's own in-process run from its initial state,
/// to its end, when the caller has made it (lagrange tune's candidate): it is
/// the sampled loop from that start, bit for bit, so it is not simulated
/// again -- one loop of seven. Ignored for a realtime scenario, whose
/// sampled loop the check runs with a period of delay.
controller::SampledSimulation simulateSampledData(
    const config::Scenario& scenario, int jobs = 0,
    const std::optional<LoopOutcome>& initial_run = std::nullopt);

/// Thrown by judgeRun when its stop check turns true: the simulations end
/// and no verdict is made (a sweep runs the row again on a restart).
struct SimulationStopped : lagrange::RuntimeFault {
  SimulationStopped() : lagrange::RuntimeFault("the sampled-data simulation was stopped") {}
};

/// The refinement cap of judgeRun: the fine loop at 8 x the rate, confirmed
/// at 16 x and no further, so that a row costs a bounded 24 x its own run.
inline constexpr int kRunRefinement = 16;

/// The verdict for one run already made in process from the scenario's
/// initial state (a sweep's row: `run` is that loop at the configured rate),
/// against the fine-rate loop from the same start: 8 x the rate, confirmed at
/// 16 x (else "not assessed"), one at a time on the calling thread. No seeded
/// starts: the row is the start. A realtime scenario is judged as the
/// in-process loop it ran, without the one-period delay. `stop_requested`,
/// if given, is asked every 100 ticks of a simulation.
/// @throws SimulationStopped once `stop_requested` returns true.
controller::SampledSimulation judgeRun(const config::Scenario& scenario, const LoopOutcome& run,
                                       bool (*stop_requested)() = nullptr);

}  // namespace lagrange::wiring
