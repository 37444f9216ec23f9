/// @file
/// `lagrange`: the front end users type. It only lists the subcommands; each
/// lives in its own folder under tools/ and declares its own options
/// (tools/subcommand.hpp, tools/front_end.hpp).
///   run           launch a scenario (plant, actuator, controller and logger over LCM, or in-process)
///   check-gains   print the gain conditions of a scenario without running it
///   replay        rebuild a component from a log and compare its outputs bit for bit
///   report        CSV files and plots of a run
///   export        a run as one HDF5 file
///   compare       run a scenario for several controllers and tabulate them
///   sweep         many in-process runs over axes of scenario keys (locally or on Slurm)
///   tune          search a scenario's controller gains for the fastest that pass the checks
///   keygen        write a secret key for a run spread over hosts
///   keys          every key a scenario file may hold
///   spy, view     watch a run: lcm-spy, or the arm in a web browser

#include "tools/check_gains/check_gains.hpp"
#include "tools/compare/compare.hpp"
#include "tools/export/export.hpp"
#include "tools/front_end.hpp"
#include "tools/keygen/keygen.hpp"
#include "tools/keys/keys.hpp"
#include "tools/replay/replay.hpp"
#include "tools/report/report.hpp"
#include "tools/run/run_command.hpp"
#include "tools/spy/spy.hpp"
#include "tools/sweep/sweep.hpp"
#include "tools/tune/tune.hpp"
#include "tools/view/view.hpp"

int main(int argc, char** argv) {
  using namespace lagrange::tools;
  FrontEnd front_end;
#ifdef LAGRANGE_BENCH_UNSIGNED
  front_end.sign = false;  // the benchmark's build: runs without a key (bench/CMakeLists.txt)
#endif
  // Every subcommand, in the order --help lists them: a new one is one line here.
  return dispatch(argc, argv,
                  {addRunCommand, addCheckGainsCommand, addReplayCommand, addReportCommand, addExportCommand,
                   addCompareCommand, addSweepCommand, addSweepShardCommand, addTuneCommand, addKeygenCommand,
                   addKeysCommand, addSpyCommand, addViewCommand},
                  front_end);
}
