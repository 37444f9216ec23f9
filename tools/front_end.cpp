/// @file
/// tools/front_end.hpp.
#include "tools/front_end.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>

#include "tools/command_error.hpp"
#include "util/error.hpp"
#include "util/text_wrap.hpp"

namespace lagrange::tools {

void describeCommand(CLI::App& cmd, const std::string& details, const std::vector<std::string>& examples) {
  cmd.footer(util::helpFooter(details, examples));
}

int dispatch(int argc, char** argv, const std::vector<AddSubcommand>& commands, const FrontEnd& front_end) {
  CLI::App app{front_end.description, front_end.name};
  app.require_subcommand(1);
  const std::string version = std::string(front_end.name) + " " + LAGRANGE_VERSION;
  app.set_version_flag("--version", version, "Print the program's name and version, then exit");
  app.footer("\n" + util::wrapped("'" + std::string(front_end.name) +
                                      " COMMAND --help' shows a command's options and examples; "
                                      "docs/README.md maps the documentation.",
                                  "", 80));
  std::vector<Subcommand> declared;
  for (const AddSubcommand add : commands) {
    declared.push_back(add(app));
    // `lagrange run --version` too: what a user types to learn which
    // program answers (it would otherwise ask for run's required options).
    declared.back().cli->set_version_flag("--version", version,
                                          "Print the program's name and version, then exit");
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every other parse error is bad input (CLI11's own codes are 100+).
    return app.exit(e) == 0 ? kExitOk : kExitBadInput;
  }
  Invocation invocation;
  // Without /proc (a chroot), argv[0] stands in: only the commands that
  // re-execute the program need the path.
  std::error_code no_proc;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", no_proc);
  invocation.self_exe = no_proc ? std::string(argv[0]) : self.string();
  invocation.argv.assign(argv, argv + argc);
  invocation.argv[0] = invocation.self_exe;
  invocation.sign = front_end.sign;
  for (const Subcommand& command : declared) {
    if (!*command.cli) continue;
    // A command catches what it can explain; anything that still escapes
    // ends here, named and with the exit code of its kind, never as a crash.
    try {
      return command.run(invocation);
    } catch (const std::exception& e) {
      return failWith(std::string(front_end.name) + " " + command.cli->get_name(), e);
    }
  }
  return kExitBadInput;  // unreachable: CLI11 requires one subcommand
}

}  // namespace lagrange::tools
