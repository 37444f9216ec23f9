#pragma once
/// @file
/// What every lagrange process shares: the command line (--config,
/// --lcm-url), stop signals, STATUS reporting (status_reporter.hpp) and the top-level error policy
/// (a user error prints what was wrong and what was expected, then exits 2;
/// a runtime failure exits 1). Process mains stay thin by building on it.

#include <functional>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "config/scenario.hpp"
#include "runtime/status_reporter.hpp"
#include "transport/lcm_node.hpp"

namespace lagrange::runtime {

/// Default LCM URL: LCM's own default group and port, TTL 0 (never leaves the host).
inline constexpr const char* kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0";

/// True once SIGINT or SIGTERM arrived.
bool stopRequested();

/// Raises the calling thread's nice value to `nice` unless it is already at
/// least that (threads it starts later inherit it); warns, naming `key`, if
/// the system refuses. Lowering priority needs no privilege.
void niceAtLeast(int nice, const std::string& key);
/// The calling thread's nice value.
int niceValue();

/// True once per SIGCONT received since the last call: the process was
/// stopped and resumed, or the launcher restarted one of its peers (it sends
/// SIGCONT to the plant then). Either way the wall time since the plant's
/// last progress is nobody's fault, and its deadlines start over with the
/// start-up allowance. SIGCONT, not a signal of our own: its default action
/// is harmless, so a notice that arrives before the handler is installed
/// cannot kill the process.
bool takeResumeNotice();

/// The body of a process: gets the validated scenario and a connected node;
/// returns the exit code.
using ProcessBody = std::function<int(const config::Scenario&, transport::LcmNode&)>;

/// Start-up work that takes a while (the gain report: its k_c estimate on a
/// URDF arm is about a second of CPU). It runs after the scenario is loaded
/// and before the process enters SCHED_FIFO: threads of one FIFO priority do
/// not preempt each other, so work done there would hold a core from the
/// realtime loops of the processes already running (a 1.2 s stall of the
/// actuator's loop at the start of a realtime Panda run, before this hook).
using ProcessPrepare = std::function<void(const config::Scenario&)>;

/// An option of one process beyond the common ones: "--name VALUE" into a
/// string, a number or a whole number, or a flag into a bool. (Declared here
/// rather than on CLI11's App, so that CLI11, header-only in Debian 12 and
/// about ten seconds of compile time in every file that uses it, is compiled
/// once, in process.cpp, rather than in every process main.)
struct ProcessOption {
  std::string names;                                        ///< CLI11's: "-o,--out", "--strict"
  std::variant<std::string*, double*, int*, bool*> target;  ///< bool: a flag
  std::string help;
  bool show_default = false;  ///< --help shows the value `target` holds before parsing
};

/// Parses the common options (plus `options`), installs the
/// signal handlers, loads the scenario, runs `prepare` (may be empty),
/// connects LCM and runs `body`,
/// translating exceptions into messages and exit codes. A positive
/// receive_buffer_bytes asks the kernel for that UDP receive buffer
/// (LCM's recv_buf_size; capped by net.core.rmem_max, and LCM warns then).
int runProcess(const std::string& name, const std::string& description, int argc, char** argv,
               const std::vector<ProcessOption>& options, const ProcessPrepare& prepare,
               const ProcessBody& body, int receive_buffer_bytes = 0);

/// The LCM URL with recv_buf_size=bytes added (udpm URLs without one only).
std::string withReceiveBuffer(const std::string& url, int bytes);

}  // namespace lagrange::runtime
