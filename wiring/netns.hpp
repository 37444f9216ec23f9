#pragma once
/// @file
/// Private network namespaces for runs: LCM traffic of a run stays on the
/// loopback of its own namespace, so parallel runs never cross and no packet
/// leaves the host.

#include <cstdint>
#include <string>
#include <vector>

namespace lagrange::wiring {

/// True when this process was started by reexecInPrivateNetns.
bool insidePrivateNetns();

/// Replaces this process with `unshare -n` (as root) or `unshare -rn` (as a
/// user, through a user namespace) running the same command line again.
/// Returns only on failure, with the reason.
std::string reexecInPrivateNetns(const std::vector<std::string>& argv);

/// Moves this (single-threaded) process into the network namespace of
/// process `pid` -- through its user namespace first when it has its own
/// (a run started without root). @throws RuntimeFault naming the step
/// that failed and why.
void joinNetnsOf(long pid);

/// A multicast LCM URL on a random port, TTL 0: a run's own bus.
std::string freshLcmUrl();

/// A run id drawn at random: positive, never 0 (0 means "any run").
int64_t randomRunId();

/// Brings up lo with multicast and routes 224.0.0.0/4 to it.
/// @throws RuntimeFault naming the failed `ip` command.
void configureLoopbackMulticast();

}  // namespace lagrange::wiring
