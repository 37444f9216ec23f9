#include "tools/view/view_host_check.hpp"

#include <ifaddrs.h>
#include <netdb.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace lagrange::tools {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// An address as it appears in a Host header: IPv6 in brackets.
std::string asHostName(const std::string& host) {
  if (host.find(':') != std::string::npos && host.front() != '[') return "[" + lower(host) + "]";
  return lower(host);
}

bool isWildcard(const std::string& host) { return host == "0.0.0.0" || host == "::" || host == "[::]"; }

// The numeric addresses of this machine's interfaces (without an IPv6 zone:
// a browser writes none in a Host header it sends).
void addInterfaceAddresses(std::set<std::string>& out) {
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) return;
  for (const ifaddrs* a = list; a != nullptr; a = a->ifa_next) {
    if (a->ifa_addr == nullptr || (a->ifa_addr->sa_family != AF_INET && a->ifa_addr->sa_family != AF_INET6))
      continue;
    char text[NI_MAXHOST];
    const socklen_t length = a->ifa_addr->sa_family == AF_INET ? sizeof(sockaddr_in) : sizeof(sockaddr_in6);
    if (getnameinfo(a->ifa_addr, length, text, sizeof text, nullptr, 0, NI_NUMERICHOST) != 0) continue;
    std::string address = text;
    address = address.substr(0, address.find('%'));
    out.insert(asHostName(address));
  }
  freeifaddrs(list);
}

}  // namespace

HostPolicy hostPolicy(const std::string& bound_host, bool allow_remote) {
  HostPolicy p;
  p.accepted = {"localhost", "127.0.0.1", "[::1]"};
  if (!isWildcard(bound_host)) p.accepted.insert(asHostName(bound_host));
  if (allow_remote && isWildcard(bound_host)) {
    char name[256] = {};
    if (gethostname(name, sizeof name - 1) == 0 && name[0] != '\0') p.accepted.insert(lower(name));
    addInterfaceAddresses(p.accepted);
  }
  return p;
}

std::string hostRefusal(const std::vector<std::string>& host_headers, const HostPolicy& policy) {
  std::string expected;
  for (const std::string& name : policy.accepted) expected += (expected.empty() ? "" : ", ") + name;
  expected = "expected one of " + expected + " (with or without a port)";
  if (host_headers.empty()) return "the request has no Host header; " + expected;
  if (host_headers.size() > 1)
    return "the request has " + std::to_string(host_headers.size()) +
           " Host headers; exactly one is answered, " + expected;
  const std::string& host_header = host_headers.front();
  for (std::size_t i = 0; i < host_header.size(); ++i) {
    const auto byte = static_cast<unsigned char>(host_header[i]);
    if (byte <= 0x20 || byte >= 0x7f) {
      char shown[8];
      std::snprintf(shown, sizeof shown, "0x%02x", byte);
      return "the Host header holds the byte " + std::string(shown) + " at " + std::to_string(i) +
             ", which is not printable ASCII; " + expected;
    }
  }
  if (host_header.empty()) return "the request has an empty Host header; " + expected;
  // The name: up to the port's colon, which for an IPv6 address follows its bracket.
  const std::size_t close_bracket = host_header.front() == '[' ? host_header.find(']') : std::string::npos;
  const std::size_t colon = host_header.find(':', close_bracket == std::string::npos ? 0 : close_bracket);
  if (host_header.front() == '[' && close_bracket == std::string::npos)
    return "Host " + host_header + " is not a host name; " + expected;
  const std::string name = lower(host_header.substr(0, colon));
  if (colon != std::string::npos) {
    const std::string port = host_header.substr(colon + 1);
    if (port.empty() || port.size() > 5 || !std::all_of(port.begin(), port.end(), ::isdigit))
      return "Host " + host_header + " has no valid port after its colon; " + expected;
  }
  if (policy.accepted.count(name) == 0)
    return "Host " + host_header +
           " is not a name of this viewer (a page of another site reaching it through DNS rebinding "
           "looks like this); " +
           expected;
  return "";
}

}  // namespace lagrange::tools
