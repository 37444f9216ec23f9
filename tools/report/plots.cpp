#include "tools/report/plots.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>

#include "util/output_stream.hpp"

namespace lagrange::tools {

namespace {

namespace fs = std::filesystem;

// Runs gnuplot in `dir` with `script` on its standard input; its messages are
// appended to `log`. Returns gnuplot's exit status (127: not installed).
int runGnuplot(const std::string& dir, const std::string& script, const std::string& log) {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) throw PlotError(std::string("pipe: ") + std::strerror(errno));
  const pid_t pid = fork();
  if (pid < 0) throw PlotError(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    dup2(pipe_fds[0], STDIN_FILENO);
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    const int log_fd = open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (log_fd >= 0) dup2(log_fd, STDERR_FILENO), dup2(log_fd, STDOUT_FILENO);
    if (chdir(dir.c_str()) != 0) _exit(126);
    execlp("gnuplot", "gnuplot", static_cast<char*>(nullptr));
    _exit(127);
  }
  close(pipe_fds[0]);
  std::signal(SIGPIPE, SIG_IGN);
  const char* data = script.data();
  size_t left = script.size();
  while (left > 0) {
    const ssize_t n = write(pipe_fds[1], data, left);
    if (n <= 0) break;
    data += n;
    left -= static_cast<size_t>(n);
  }
  close(pipe_fds[1]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

Plots drawPlots(const PlotSpec& spec) {
  const PlotScript script = plotScript(spec);
  {
    util::OutputStream out(fs::path(spec.dir) / "plots.gp");
    out << script.text;
    if (!out) throw PlotError("cannot write " + spec.dir + "/plots.gp");
  }
  return drawPictures(spec.dir, script.pngs, script.sections);
}

Plots drawPictures(const std::string& dir, const std::vector<std::string>& pngs,
                   const std::vector<std::string>& sections) {
  Plots plots;
  plots.log = (fs::path(dir) / "gnuplot.log").string();
  fs::remove(plots.log);
  // One gnuplot per picture, so a plot gnuplot rejects costs only itself.
  for (size_t i = 0; i < pngs.size(); ++i) {
    const fs::path png = fs::path(dir) / pngs[i];
    fs::remove(png);
    const int status = runGnuplot(dir, sections[i], plots.log);
    if (status == 127)
      throw PlotError(
          "gnuplot not found; install Debian's gnuplot-nox (bash scripts/setup.sh does) to get the "
          "plots; the CSV files are written");
    if (status == 0 && fs::exists(png) && fs::file_size(png) > 0)
      plots.written.push_back(png.string());
    else
      plots.failed.push_back(pngs[i]);
  }
  return plots;
}

}  // namespace lagrange::tools
