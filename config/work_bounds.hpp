#pragma once
/// @file
/// The work a scenario asks for, bounded before anything starts: samples,
/// physics steps, joints, the log's size and the memory of what is recorded
/// per sample. Each key's range (config/key_ranges.hpp) keeps single numbers
/// sane; these bounds catch the products of sane numbers (a day at 100 kHz).
/// A scenario past one is refused with the number it would need and the
/// bound. docs/configuration.md ("Work") states them.

#include <cstdint>

#include "config/scenario.hpp"

namespace lagrange::config {

/// Samples (ticks) of one run: 1e8 is 28 hours at 1 kHz; shipped runs take at most 1.5e4.
inline constexpr double kMaxSamples = 1e8;
/// Physics steps per sample: 1e5 is a 10 ns step at 1 kHz.
inline constexpr double kMaxStepsPerSample = 1e5;
/// Physics steps of one run: 1e9 is 28 hours at a 0.1 ms step, about an hour
/// of computing for a small arm; shipped runs take at most 4e5.
inline constexpr double kMaxPhysicsSteps = 1e9;
/// Joints of an arm (links of a planar chain, moving joints of a URDF chain):
/// the gain check's proven k_c costs O(n^5) memory and O(n^6) time in the
/// closed form of C (0.3 s at 16 joints, 13 s at 32, 6 GB at 50), and its
/// search for the largest ratio O(n^4) an evaluation (model/bounds.hpp); the
/// longest real arms have 7 to 9 joints.
inline constexpr int kMaxJoints = 16;
/// The highest integrator-chain order of an actuator (actuator.order 0..4):
/// the paper's chains go to 4; it sizes ACTUATOR_STATE's xi and
/// CONTROL_COMMAND's xi_error (logs/event_bounds.hpp bounds them by it).
inline constexpr int kMaxActuatorOrder = 4;
/// The estimated size of run.lcm.
inline constexpr double kMaxLogBytes = 16.0 * (1u << 30);
/// The estimated memory of the series a process keeps for the whole run (the
/// logger's per-sample records, a free_motion reference's table).
inline constexpr double kMaxSeriesBytes = 4.0 * (1u << 30);

/// Estimates, per sample and per run (also shown in the errors).
double logBytesPerSample(const Scenario& s);
double seriesBytes(const Scenario& s);  ///< the larger of the logger's and the reference table's

/// @throws ConfigError "config: KEY: ..." naming what the scenario asks for
/// and the bound, for the first bound it crosses.
void checkWorkBounds(const Scenario& s);

}  // namespace lagrange::config
