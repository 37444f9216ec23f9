#pragma once
/// @file
/// Which Host headers `lagrange view` answers. A page bound to loopback is
/// still reachable from any web page the user visits, through DNS
/// rebinding: a name the attacker controls is made to resolve to 127.0.0.1,
/// and the browser then sends the attacker's name as Host. Answering only
/// the names this server is known by closes that door.

#include <set>
#include <string>
#include <vector>

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

/// Empty if a request whose Host headers are `host_headers` is to be
/// answered; else why not, with what was expected, for the 421 response.
/// `host_headers`: every Host header of the request, each value whole as
/// the server parsed it (a NUL kept: cpp-httplib's get_header_value would
/// cut the value at one, and percent-decodes values, so `localhost%00.evil`
/// arrives as `localhost`, NUL, `.evil`). Answered only when there is
/// exactly one (a second one, first or last, is refused: proxies and
/// browsers may read another than we do), made of printable ASCII alone
/// (no space, no control character, nothing past 0x7e), naming one of the
/// policy's names with or without a port (a tunnel such as ssh -L may
/// change the port).
std::string hostRefusal(const std::vector<std::string>& host_headers, const HostPolicy& policy);

}  // namespace lagrange::tools
