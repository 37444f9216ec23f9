/// @file
/// `lagrange compare`'s command line (tools/compare/compare.hpp).
#include <CLI/CLI.hpp>
#include <memory>

#include "tools/compare/compare.hpp"

namespace lagrange::tools {

Subcommand addCompareCommand(CLI::App& app) {
  auto compare = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand("compare", "Run one scenario for several controllers");
  describeCommand(
      *cmd,
      "Run one scenario for several controllers (in-process, several at a time), each tuned by its section "
      "compare.controllers.TYPE; write a table (Markdown and CSV: convergence time, final and RMS error, max "
      "torque, torque total variation, control energy), overlay plots of the error and the torques, and with "
      "--sweep the steady-state error against one key (docs/comparison.md)",
      {"lagrange compare configs/compare_pelican.yaml --out runs/compare"});
  cmd->add_option("config", compare->config_path, "Scenario YAML file, e.g. configs/compare_pelican.yaml")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--out", compare->out_dir, "Output directory (created if missing)")->required();
  cmd->add_option("--controllers", compare->controllers,
                  "Controller types to compare, comma-separated (default: every one in compare.controllers)")
      ->delimiter(',');
  cmd->add_option("--set", compare->overrides,
                  "Override a config key in every run (after the controller's section): key=value; "
                  "repeatable");
  cmd->add_option("--sweep", compare->sweep,
                  "Also run each controller for every value of one key, KEY=[V1, V2, ...] (a YAML list), "
                  "e.g. 'sensors.position.counts_per_revolution=[4096, 65536]' (default: compare.sweep)");
  cmd->add_option("-j,--jobs", compare->jobs, "Runs at a time (default: one per core)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("-q,--quiet", compare->quiet, "Print errors only");
  return {cmd, [compare](const Invocation& inv) {
            CompareOptions o = *compare;
            o.self_exe = inv.self_exe;
            return runComparison(o);
          }};
}

}  // namespace lagrange::tools
