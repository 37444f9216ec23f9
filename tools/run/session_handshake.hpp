#pragma once
/// @file
/// The launchers of a run spread over hosts meet on the run's LCM URL before
/// any of its processes starts (tools/run/session_agreement.hpp): RUN_JOIN
/// messages signed with the shared key, re-sent every 100 ms, until every
/// launcher has heard every other. The LCM instance is closed before the
/// processes start: a launcher never listens to the run's own traffic.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tools/run/session_agreement.hpp"
#include "transport/message_auth.hpp"

namespace lagrange::tools {

struct AgreedRun {
  Nonce value{};                     ///< the same at every launcher of the run
  std::vector<std::string> members;  ///< the other launchers, e.g. "controller,logger on hostB (pid 4242)"
};

struct HandshakeOptions {
  std::string lcm_url;
  int64_t meeting_id = 0;  ///< RUN_JOIN's run id: --run-id, or derived from the URL and the scenario
  std::vector<std::string> processes;  ///< this launcher's
  int64_t scenario_digest = 0;
  double timeout = 60.0;  ///< seconds (--join-timeout)
  bool quiet = false;     ///< no "waiting for" lines
};

/// Agrees with the other launchers on the run's value. Nothing when
/// `stopped` turned true first (Ctrl-C). Throws lagrange::BadInput when two
/// launchers start one process or run different scenarios, and
/// lagrange::RuntimeFault past the timeout, naming what it waited for and
/// what it heard instead (launchers that never heard this one, datagrams
/// that failed the MAC: a launcher with another key file).
std::optional<AgreedRun> agreeWithOtherLaunchers(const HandshakeOptions& options,
                                                 const transport::MessageKey& shared_key,
                                                 const std::function<bool()>& stopped);

/// The run id the processes use when no --run-id was given: from the agreed
/// value, so two runs never share one; positive, never 0 ("any run").
int64_t runIdFromValue(const Nonce& value);

}  // namespace lagrange::tools
