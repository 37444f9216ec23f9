#pragma once
/// @file
/// What the live tracking metrics take from each per-tick message: the
/// truth's q, the command's chain errors, the applied torque. Every other
/// message is only recorded (the overload for any message does nothing), so
/// the logger subscribes to every per-tick channel the same way. A sample's
/// time is its tick's (TrackingMetrics::timeOf), never the sender's stamp.

#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_truth_t.hpp"
#include "logger/tracking_metrics.hpp"
#include "transport/messages.hpp"

namespace lagrange::logger {

inline void observe(TrackingMetrics& metrics, const lagrange::plant_truth_t& m) {
  metrics.addSample(m.header.tick, metrics.timeOf(m.header.tick), transport::toEigen(m.q),
                    transport::toEigen(m.qdot));
}
inline void observe(TrackingMetrics& metrics, const lagrange::control_command_t& m) {
  metrics.addChainErrors(m.header.tick, metrics.timeOf(m.header.tick), m.xi_error);
}
inline void observe(TrackingMetrics& metrics, const lagrange::actuator_state_t& m) {
  metrics.addTorque(m.header.tick, transport::toEigen(m.tau_applied));
}
template <class Msg>
void observe(TrackingMetrics&, const Msg&) {}

}  // namespace lagrange::logger
