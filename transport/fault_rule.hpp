#pragma once
/// @file
/// The rule of fault injection on one channel, plain data with no
/// dependency: the scenario reads it (config::ChannelFaults is this type)
/// and the transport applies it (transport/fault_injector.hpp). The one
/// header of transport/ that config includes, so that the rule is defined
/// once (tests/check_layers.sh allows exactly this one).

namespace lagrange::transport {

/// What may happen to a datagram on one channel (probabilities in [0, 1],
/// times in s). The scenario's faults.channels.NAME (config::FaultRule)
/// becomes one of these in runtime/process.cpp: transport knows no config.
struct FaultRule {
  double drop = 0.0;
  double duplicate = 0.0;
  double reorder = 0.0;
  double corrupt = 0.0;
  double delay = 0.0;
  double delay_jitter = 0.0;
  bool any() const {
    return drop > 0 || duplicate > 0 || reorder > 0 || corrupt > 0 || delay > 0 || delay_jitter > 0;
  }
};

}  // namespace lagrange::transport
