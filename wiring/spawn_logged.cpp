#include "wiring/spawn_logged.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <unistd.h>

#include <cstring>
#include <stdexcept>

#include "util/error.hpp"
#include "util/output_file.hpp"

extern char** environ;

namespace lagrange::wiring {

pid_t spawnLogged(const std::vector<std::string>& args, const SpawnLog& log, bool own_group) {
  std::vector<std::string> copy = args;
  std::vector<char*> argv;
  for (std::string& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  // Opened here, never through a link planted in its place (a shared sweep
  // folder: util/output_file.hpp), and handed to the child.
  const int fd = log.append ? util::openOutputFileToAppend(log.path) : util::createOutputFile(log.path);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  if (own_group) {
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attr, 0);
  }
  pid_t pid = -1;
  const int err = posix_spawnp(&pid, argv[0], &actions, &attr, argv.data(), environ);
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&actions);
  close(fd);
  if (err != 0) throw RuntimeFault("cannot start " + args[0] + ": " + std::strerror(err));
  return pid;
}

}  // namespace lagrange::wiring
