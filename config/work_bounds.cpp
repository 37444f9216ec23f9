#include "config/work_bounds.hpp"

#include <algorithm>
#include <cstdio>

#include "config/key_ranges.hpp"

namespace lagrange::config {

namespace {
constexpr double kFreeMotionStep = 1e-4;  // model::Reference integrates free_motion at 0.1 ms (reference.cpp)

std::string gib(double bytes) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3g GiB", bytes / (1u << 30));
  return buf;
}

[[noreturn]] void refuse(const std::string& key, const std::string& what) {
  throw ConfigError("config: " + key + ": " + what);
}
}  // namespace

double logBytesPerSample(const Scenario& s) {
  // About 8 messages a sample (positions, truth, command, actuator state,
  // statuses, acknowledgements), each with its log record and header (~200
  // bytes), and their per-joint arrays: a generous upper estimate.
  const double n = s.dof(), steps = s.torqueStepsPerTick(), order = s.actuator.order;
  return 8 * 200.0 + 8.0 * n * (2.0 * steps + 2.0 * order + 12.0);
}

double seriesBytes(const Scenario& s) {
  const double samples = s.duration * s.plant.publish_rate, n = s.dof();
  // The logger: an error sample and a torque matrix (S x n) per sample in
  // ordered maps, and a norm per chain stage.
  const double logger = samples * (240.0 + 8.0 * n * s.torqueStepsPerTick() + 8.0 * (s.actuator.order + 1.0));
  // free_motion: one state vector (2n doubles) per 0.1 ms over the run and a second more.
  const double reference = s.reference.type == model::ReferenceType::kFreeMotion
                               ? (s.duration + 1.0) / kFreeMotionStep * (48.0 + 16.0 * n)
                               : 0.0;
  return std::max(logger, reference);
}

void checkWorkBounds(const Scenario& s) {
  const double samples = s.duration * s.plant.publish_rate;
  if (samples > kMaxSamples)
    refuse("duration", "duration " + shortNumber(s.duration) + " s at plant.publish_rate " +
                           shortNumber(s.plant.publish_rate) + " Hz is " + shortNumber(samples) +
                           " samples; at most " + shortNumber(kMaxSamples) + " are allowed");
  const double per_sample = s.tickPeriod() / s.plant.physics_step;
  if (per_sample > kMaxStepsPerSample)
    refuse("plant.physics_step", "physics_step " + shortNumber(s.plant.physics_step) + " s at publish_rate " +
                                     shortNumber(s.plant.publish_rate) + " Hz is " + shortNumber(per_sample) +
                                     " physics steps a sample; at most " + shortNumber(kMaxStepsPerSample) +
                                     " are allowed");
  const double steps = s.duration / s.plant.physics_step;
  if (steps > kMaxPhysicsSteps)
    refuse("duration", "duration " + shortNumber(s.duration) + " s at plant.physics_step " +
                           shortNumber(s.plant.physics_step) + " s is " + shortNumber(steps) +
                           " physics steps; at most " + shortNumber(kMaxPhysicsSteps) + " are allowed");
  const double series = seriesBytes(s);
  if (series > kMaxSeriesBytes)
    refuse("duration",
           "duration " + shortNumber(s.duration) + " s would keep about " + gib(series) +
               " of recorded series in memory (" +
               (s.reference.type == model::ReferenceType::kFreeMotion ? "the free_motion reference's table, "
                                                                      : "") +
               "the logger's samples); at most " + gib(kMaxSeriesBytes) + " are allowed");
  const double log = samples * logBytesPerSample(s);
  if (log > kMaxLogBytes)
    refuse("duration", "duration " + shortNumber(s.duration) + " s would write a log of about " + gib(log) +
                           "; at most " + gib(kMaxLogBytes) + " are allowed");
}

}  // namespace lagrange::config
