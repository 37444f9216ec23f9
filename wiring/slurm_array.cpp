#include "wiring/slurm_array.hpp"

#include <sys/wait.h>

#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "util/error.hpp"
#include "util/output_file.hpp"
#include "wiring/spawn_logged.hpp"

namespace lagrange::wiring {

std::vector<std::string> sbatchCommand(const SlurmArray& array, const SlurmOptions& options) {
  std::vector<std::string> args = {"sbatch",
                                   "--parsable",
                                   "--job-name=" + array.job_name,
                                   "--array=" + array.indices,
                                   "--output=" + array.output,
                                   "--chdir=" + array.chdir};
  if (!options.partition.empty()) args.push_back("--partition=" + options.partition);
  if (!options.time_limit.empty()) args.push_back("--time=" + options.time_limit);
  if (!options.account.empty()) args.push_back("--account=" + options.account);
  args.insert(args.end(), options.sbatch_args.begin(), options.sbatch_args.end());
  if (!options.no_wait) args.push_back("--wait");
  args.push_back(array.script);
  return args;
}

pid_t submitSlurmArray(const SlurmArray& array, const SlurmOptions& options) {
  try {
    return spawnLogged(sbatchCommand(array, options), {array.sbatch_output}, /*own_group=*/true);
  } catch (const RuntimeFault& e) {
    throw RuntimeFault(std::string(e.what()) + "; expected Slurm's sbatch on PATH (Debian: slurm-client)");
  }
}

SlurmWait waitForSlurmArray(pid_t pid, const SlurmArray& array,
                            const std::function<void(const std::string& job)>& on_submitted,
                            const std::function<void()>& on_poll, const std::function<bool()>& stop) {
  SlurmWait w;
  for (;;) {
    const pid_t done = waitpid(pid, &w.wstatus, WNOHANG);
    if (w.job.empty()) {
      w.job = slurmJobIdOf(sbatchOutputOf(array));
      if (!w.job.empty() && on_submitted) on_submitted(w.job);
    }
    if (done == pid) return w;
    if (stop && stop()) {
      w.stopped = true;
      return w;
    }
    if (on_poll) on_poll();
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
}

std::string sbatchOutputOf(const SlurmArray& array) {
  std::ifstream in(array.sbatch_output, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string waitStatusText(int wstatus) {
  if (WIFEXITED(wstatus)) return "exited with code " + std::to_string(WEXITSTATUS(wstatus));
  return std::string("was killed by signal ") + std::to_string(WTERMSIG(wstatus)) + " (" +
         strsignal(WTERMSIG(wstatus)) + ")";
}

std::string slurmJobIdOf(const std::string& sbatch_output) {
  std::istringstream lines(sbatch_output);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty() && !lines.eof() && std::isdigit(static_cast<unsigned char>(line[0])) &&
        line.find_first_not_of("0123456789") == line.find(';'))
      return line.substr(0, line.find(';'));
  return "";
}

bool slurmJobQueued(const std::string& job) {
  if (job.empty() || job.find_first_not_of("0123456789") != std::string::npos) return false;
  FILE* pipe = popen(("squeue -h -o %i -j " + job + " 2>/dev/null").c_str(), "r");
  if (!pipe) return false;
  std::string out;
  char buf[256];
  while (fgets(buf, sizeof buf, pipe)) out += buf;
  const int status = pclose(pipe);
  return status == 0 && out.find_first_not_of(" \n") != std::string::npos;
}

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

void writeJobScript(const std::string& path, const std::string& text) {
  util::writeOutputFile(path, text);
  namespace fs = std::filesystem;
  fs::permissions(path, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                            fs::perms::others_read | fs::perms::others_exec);
}

}  // namespace lagrange::wiring
