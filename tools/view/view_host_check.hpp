#pragma once
/// @file
/// Which Host headers `lagrange view` answers. A page bound to loopback is
/// still reachable from any web page the user visits, through DNS
/// rebinding: a name the attacker controls is made to resolve to 127.0.0.1,
/// and the browser then sends the attacker's name as Host. Answering only
/// the names this server is known by closes that door.

#include <set>
#include <string>

namespace lagrange::tools {

/// The host names and addresses (lower case, IPv6 in brackets, no port) a
/// request's Host header may name.
struct HostPolicy {
  std::set<std::string> accepted;
};

/// Always: localhost, 127.0.0.1, [::1] and the bound `--host` itself. With
/// --allow-remote and a wildcard bind (0.0.0.0, ::), also this machine's
/// host name (gethostname) and the addresses of its network interfaces.
HostPolicy hostPolicy(const std::string& bound_host, bool allow_remote);

/// Empty if a request with this Host header value (with or without a port:
/// a tunnel such as ssh -L may change the port) is to be answered; else why
/// not, with what was expected, for the 421 response.
std::string hostRefusal(const std::string& host_header, const HostPolicy& policy);

}  // namespace lagrange::tools
