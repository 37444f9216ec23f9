#include "wiring/netns.hpp"

#include <fcntl.h>
#include <sched.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <random>
#include <stdexcept>

#include "util/error.hpp"

namespace lagrange::wiring {

namespace {
constexpr const char* kEnvMarker = "LAGRANGE_PRIVATE_NETNS";

std::string findIp() {
  for (const char* p : {"/usr/sbin/ip", "/sbin/ip", "/usr/bin/ip", "/bin/ip"})
    if (access(p, X_OK) == 0) return p;
  throw RuntimeFault(
      "the 'ip' command (Debian package iproute2) is needed to set up the "
      "private network namespace; install it or run with --no-netns");
}

void runIp(const std::string& ip, const std::vector<std::string>& args) {
  std::vector<char*> argv{const_cast<char*>(ip.c_str())};
  std::string cmd = "ip";
  for (const auto& a : args) {
    argv.push_back(const_cast<char*>(a.c_str()));
    cmd += " " + a;
  }
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw RuntimeFault("fork failed: " + std::string(std::strerror(errno)));
  if (pid == 0) {
    execv(ip.c_str(), argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw RuntimeFault("'" + cmd + "' failed in the private network namespace");
}
}  // namespace

bool insidePrivateNetns() { return std::getenv(kEnvMarker) != nullptr; }

std::string reexecInPrivateNetns(const std::vector<std::string>& args) {
  setenv(kEnvMarker, "1", 1);
  std::vector<std::string> cmd{"unshare", geteuid() == 0 ? "-n" : "-rn", "--"};
  cmd.insert(cmd.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& c : cmd) argv.push_back(c.data());
  argv.push_back(nullptr);
  execvp("unshare", argv.data());
  return "cannot run 'unshare' (util-linux): " + std::string(std::strerror(errno));
}

namespace {
// The namespace file of `kind` of process `pid`, and whether it is the one this process is in.
struct NamespaceFile {
  std::string path;
  bool same_as_ours;
};
NamespaceFile namespaceOf(long pid, const char* kind) {
  const std::string path = "/proc/" + std::to_string(pid) + "/ns/" + kind;
  struct stat theirs {
  }, ours{};
  if (stat(path.c_str(), &theirs) != 0)
    throw RuntimeFault("cannot read " + path + ": " + std::strerror(errno));
  const std::string own = std::string("/proc/self/ns/") + kind;
  const bool same =
      stat(own.c_str(), &ours) == 0 && ours.st_ino == theirs.st_ino && ours.st_dev == theirs.st_dev;
  return {path, same};
}

void enter(const NamespaceFile& ns, int type) {
  if (ns.same_as_ours) return;
  const int fd = open(ns.path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw RuntimeFault("cannot open " + ns.path + ": " + std::strerror(errno));
  const int rc = setns(fd, type);
  const int err = errno;
  close(fd);
  if (rc != 0)
    throw RuntimeFault("cannot enter " + ns.path + ": " + std::strerror(err) +
                       (err == EPERM ? " (join a run started by the same user, or as root)" : ""));
}
}  // namespace

void joinNetnsOf(long pid) {
  const NamespaceFile net = namespaceOf(pid, "net");
  if (net.same_as_ours) return;
  enter(namespaceOf(pid, "user"), CLONE_NEWUSER);
  enter(net, CLONE_NEWNET);
}

void configureLoopbackMulticast() {
  const std::string ip = findIp();
  runIp(ip, {"link", "set", "lo", "up"});
  runIp(ip, {"link", "set", "lo", "multicast", "on"});
  runIp(ip, {"route", "add", "224.0.0.0/4", "dev", "lo"});
}

std::string freshLcmUrl() {
  std::random_device rd;
  const unsigned port = 20000 + rd() % 40000;
  return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0";
}

int64_t randomRunId() {
  std::random_device rd;
  const uint64_t r = (static_cast<uint64_t>(rd()) << 32) ^ rd();
  return static_cast<int64_t>(r >> 1) | 1;
}

}  // namespace lagrange::wiring
