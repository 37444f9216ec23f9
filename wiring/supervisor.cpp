#include "wiring/supervisor.hpp"

#include <fcntl.h>
#include <sched.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "transport/rate_loop.hpp"
#include "util/error.hpp"

namespace lagrange::wiring {

std::string ChildExit::describe() const {
  if (signal != 0) return "was killed by signal " + std::to_string(signal) + " (" + strsignal(signal) + ")";
  return "exited with code " + std::to_string(exit_code);
}

Supervisor::~Supervisor() {
  if (anyRunning()) stopAll(2.0);
}

namespace {

// In the child, before exec: the realtime scheduling of a program from
// outside (ChildSpec::fifo_priority, cpus). Only what is safe after fork:
// system calls and fprintf to the child's own log.
void enterScheduling(const ChildSpec& spec) {
  if (!spec.cpus.empty()) {
    cpu_set_t set;
    CPU_ZERO(&set);
    for (const int c : spec.cpus)
      if (c >= 0 && c < CPU_SETSIZE) CPU_SET(c, &set);
    if (sched_setaffinity(0, sizeof set, &set) != 0)
      std::fprintf(stderr,
                   "lagrange run: warning: realtime.cpus.%s: the kernel refused these CPUs (%s); running "
                   "where the scheduler puts it\n",
                   spec.name.c_str(), std::strerror(errno));
    else
      std::fprintf(stderr, "lagrange run: the %s runs on the CPUs of realtime.cpus.%s\n", spec.name.c_str(),
                   spec.name.c_str());
  }
  if (spec.fifo_priority > 0) {
    sched_param param{};
    param.sched_priority = spec.fifo_priority;
    if (sched_setscheduler(0, SCHED_FIFO, &param) != 0)
      std::fprintf(
          stderr,
          "lagrange run: warning: SCHED_FIFO priority %d (one below realtime.priority) is not allowed "
          "here (%s; needs root or CAP_SYS_NICE); the %s runs under the normal scheduler\n",
          spec.fifo_priority, std::strerror(errno), spec.name.c_str());
    else
      std::fprintf(stderr,
                   "lagrange run: the %s runs under SCHED_FIFO priority %d (one below realtime.priority, the "
                   "built-in loops')\n",
                   spec.name.c_str(), spec.fifo_priority);
  }
}

}  // namespace

std::string schedulerOf(pid_t pid) {
  sched_param param{};
  const int policy = sched_getscheduler(pid);
  if (policy < 0) return "unknown";
  std::string out = "other";
  if (policy == SCHED_FIFO && sched_getparam(pid, &param) == 0)
    out = "fifo:" + std::to_string(param.sched_priority);
  cpu_set_t mine, its;
  CPU_ZERO(&mine);
  CPU_ZERO(&its);
  if (sched_getaffinity(0, sizeof mine, &mine) == 0 && sched_getaffinity(pid, sizeof its, &its) == 0 &&
      !CPU_EQUAL(&mine, &its)) {
    out += " cpus " + transport::cpuList(its);
  }
  return out;
}

pid_t Supervisor::pidOf(const std::string& name) const {
  for (const auto& c : children_)
    if (c.spec.name == name && c.running) return c.pid;
  return -1;
}

void Supervisor::start(const ChildSpec& spec) {
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw RuntimeFault("fork failed: " + std::string(std::strerror(errno)));
  if (pid == 0) {
    // The child must not outlive the launcher.
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(1);
    // Never through a link planted in the output directory (O_NOFOLLOW); a
    // fresh log replaces the old file rather than truncating it (O_EXCL
    // after unlink), so a hard link's other names keep their bytes.
    if (!spec.append_log) unlink(spec.log_path.c_str());
    const int fd = open(spec.log_path.c_str(),
                        O_WRONLY | O_CREAT | O_NOFOLLOW | (spec.append_log ? O_APPEND : O_EXCL), 0644);
    if (fd < 0) {
      std::fprintf(stderr, "lagrange run: cannot create '%s': %s; expected a writable output directory\n",
                   spec.log_path.c_str(), std::strerror(errno));
      _exit(kExitFailed);
    }
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
    close(fd);
    if (spec.pass_fd >= 0) dup2(spec.pass_fd, 3);  // dup2 clears close-on-exec
    const int devnull = open("/dev/null", O_RDONLY);
    if (devnull >= 0) dup2(devnull, STDIN_FILENO);
    std::signal(SIGINT, SIG_IGN);  // Ctrl-C reaches the launcher, which stops us with SIGTERM
    enterScheduling(spec);
    for (const auto& e : spec.env) putenv(const_cast<char*>(e.c_str()));  // the child's own copy of spec
    if (!spec.working_directory.empty() && chdir(spec.working_directory.c_str()) != 0) {
      std::fprintf(stderr, "cannot enter %s: %s\n", spec.working_directory.c_str(), std::strerror(errno));
      _exit(127);
    }
    std::vector<char*> argv;
    for (const auto& a : spec.argv) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execvp(argv[0], argv.data());
    std::fprintf(stderr, "cannot execute %s: %s\n", argv[0], std::strerror(errno));
    _exit(127);
  }
  children_.push_back({spec, pid, true});
}

void Supervisor::restart(const std::string& name) {
  const Child* last = nullptr;
  for (const auto& c : children_)
    if (c.spec.name == name) last = &c;
  if (last == nullptr) throw std::logic_error("no process '" + name + "' to restart");
  if (last->running) throw std::logic_error("process '" + name + "' still runs");
  ChildSpec spec = last->spec;
  spec.append_log = true;
  start(spec);
}

bool Supervisor::signal(const std::string& name, int sig) {
  for (const auto& c : children_)
    if (c.spec.name == name && c.running) return ::kill(c.pid, sig) == 0;
  return false;
}

std::vector<ChildExit> Supervisor::reap() {
  std::vector<ChildExit> out;
  for (auto& c : children_) {
    if (!c.running) continue;
    int status = 0;
    rusage usage{};
    const pid_t r = wait4(c.pid, &status, WNOHANG, &usage);
    if (r != c.pid) continue;
    c.running = false;
    ChildExit e;
    e.name = c.spec.name;
    if (WIFSIGNALED(status)) e.signal = WTERMSIG(status);
    if (WIFEXITED(status)) e.exit_code = WEXITSTATUS(status);
    e.cpu_user =
        static_cast<double>(usage.ru_utime.tv_sec) + 1e-6 * static_cast<double>(usage.ru_utime.tv_usec);
    e.cpu_system =
        static_cast<double>(usage.ru_stime.tv_sec) + 1e-6 * static_cast<double>(usage.ru_stime.tv_usec);
    out.push_back(e);
  }
  return out;
}

bool Supervisor::anyRunning() const {
  for (const auto& c : children_)
    if (c.running) return true;
  return false;
}

std::vector<ChildExit> Supervisor::waitAll(double timeout_seconds) {
  std::vector<ChildExit> exits;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_seconds);
  while (anyRunning() && std::chrono::steady_clock::now() < deadline) {
    for (auto& e : reap()) exits.push_back(e);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return exits;
}

std::vector<ChildExit> Supervisor::stopAll(double grace_seconds) {
  for (const auto& c : children_)
    if (c.running) kill(c.pid, SIGTERM);
  std::vector<ChildExit> exits = waitAll(grace_seconds);
  for (const auto& c : children_)
    if (c.running) kill(c.pid, SIGKILL);
  for (auto& e : waitAll(5.0)) exits.push_back(e);
  return exits;
}

}  // namespace lagrange::wiring
