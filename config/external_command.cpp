#include "config/external_command.hpp"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace lagrange::config {

namespace {
// A program on PATH, or "" when there is none.
std::string onPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / name;
    if (access(candidate.c_str(), X_OK) == 0 && !std::filesystem::is_directory(candidate)) return candidate;
  }
  return "";
}
}  // namespace

ExternalCommand readExternalCommand(MapReader& section, const std::string& base_dir, const std::string& role,
                                    bool check_programs) {
  ExternalCommand out;
  const YAML::Node command = section.child("command");
  if (!command.IsSequence() || command.size() == 0)
    section.fail("command", "expected the " + role + "'s command line as a list, e.g. [python3, my_" + role +
                                ".py, --gain, 100]");
  for (const YAML::Node& arg : command) {
    if (!arg.IsScalar()) section.fail("command", "expected every entry to be a string");
    out.command.push_back(arg.as<std::string>());
  }
  const std::filesystem::path base = std::filesystem::absolute(base_dir.empty() ? "." : base_dir);
  out.working_directory = section.has("working_directory")
                              ? std::filesystem::absolute(base / section.text("working_directory")).string()
                              : base.string();
  if (!check_programs) return out;
  if (!std::filesystem::is_directory(out.working_directory))
    section.fail("working_directory", "'" + out.working_directory +
                                          "' is not a directory; expected the folder the command starts in");
  std::string& program = out.command[0];
  if (program.find('/') != std::string::npos) {
    const std::filesystem::path resolved = std::filesystem::absolute(base / program).lexically_normal();
    if (access(resolved.c_str(), X_OK) != 0 || std::filesystem::is_directory(resolved))
      section.fail("command", "'" + program + "' does not exist or is not executable (looked for " +
                                  resolved.string() + "); expected the " + role + "'s program");
    program = resolved.string();
  } else if (onPath(program).empty()) {
    section.fail("command", "'" + program + "' is not a program on PATH; expected the " + role +
                                "'s program (a name on PATH, or a path with a slash, e.g. ./my_" + role +
                                ".py, relative to the scenario file's folder)");
  }
  return out;
}

}  // namespace lagrange::config
