// `lagrange export RUN [-o FILE]` (tools/export/export.hpp): the HDF5 file
// read back by h5py (Debian's python3-h5py) holds every sample of the log,
// bit for bit as lagrange.log.load (python/, an independent reader of the LCM
// log) decodes it, with its units, joint names, scenario and summary, and
// /tracking holds what Run.tracking gives, bit for bit; without -o the file
// is RUN/run.h5; an existing file is not replaced without --force.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {
namespace {

// /tracking against Run.tracking of the same log (lagrange.log, no numpy):
// every column bit for bit, q and q_desired the channels' rows at those
// ticks, the counts of what was not joined. Returns the rows checked.
const char* kTrackingCheck = R"PY(
def check_tracking(run, f):
    tr = run.tracking
    g = f["tracking"]
    assert list(g["tick"][:]) == tr["tick"], (list(g["tick"][:]), tr["tick"])
    if tr["t"] is None:
        assert "t" not in g
    else:
        assert list(g["t"][:]) == tr["t"]
        assert g.attrs["publish_rate"] == tr.publish_rate
    assert g["q_error"].shape == (len(tr["tick"]), g["q"].shape[1])
    assert [list(r) for r in g["q_error"][:]] == tr["q_error"], "q_error"
    assert list(g["error_norm"][:]) == tr["error_norm"], "error_norm"
    assert numpy.array_equal(g["q"][:] - g["q_desired"][:], g["q_error"][:])
    assert [list(r) for r in g["q"][:]] == tr["q"], "q"
    assert [list(r) for r in g["q_desired"][:]] == tr["q_desired"], "q_desired"
    assert set(g) == set(k for k in tr if tr[k] is not None), (set(g), set(tr))  # every column, no other
    if "xi_error" in tr:
        assert [[list(s) for s in r] for r in g["xi_error"][:]] == tr["xi_error"], "xi_error"
    assert g.attrs["unjoined_PLANT_TRUTH"] == tr.unjoined["PLANT_TRUTH"]
    assert g.attrs["unjoined_CONTROL_COMMAND"] == tr.unjoined["CONTROL_COMMAND"]
    assert g.attrs["mismatched"] == tr.mismatched
    assert g["error_norm"].attrs["units"] == "rad"
    return len(tr["tick"])
)PY";

// Compares every per-tick field of the run's log (lagrange.log, no numpy)
// with the HDF5 file (h5py), value for value, and /tracking with
// Run.tracking; prints what it checked.
const std::string kCompare = std::string(R"PY(
import json, sys, h5py, numpy, lagrange.log
run_dir, path = sys.argv[1], sys.argv[2]
run = lagrange.log.load(run_dir, numpy=False)
f = h5py.File(path, "r")
)PY") + kTrackingCheck + R"PY(
assert f.attrs["format"] == "lagrange run export 1", f.attrs["format"]
assert json.loads(f.attrs["summary"]) == run.summary
assert f.attrs["scenario"] == run.scenario_yaml
checked = 0
for channel, columns in sorted(run.channels.items()):
    g = f[channel]
    assert list(g["tick"][:]) == columns["header.tick"], channel
    assert list(g["t"][:]) == columns["t"], channel
    assert list(g["publish_utime"][:]) == columns["header.publish_utime"], channel
    for name, column in columns.items():
        if name.startswith("header.") or name == "t" or not column:
            continue
        if name in ("num_joints", "num_rates", "order", "torque_steps", "chain_order"):
            continue  # array sizes: the shapes of the datasets
        if isinstance(column[0], list) and column[0] and isinstance(column[0][0], (list, tuple)):
            want = numpy.array([[list(r) for r in rows] for rows in column], dtype=float)
        elif isinstance(column[0], (list, tuple)) and not column[0]:
            assert name not in g, (channel, name)  # empty fields are left out
            continue
        else:
            want = numpy.array(column, dtype=float)
        got = g[name][:]
        assert got.shape == want.shape, (channel, name, got.shape, want.shape)
        assert numpy.array_equal(got, want), (channel, name)
        assert "units" in g[name].attrs, (channel, name)
        checked += got.size
print(len(run.channels), checked, list(f.attrs["joint_names"]), f["PLANT_TRUTH/q"].attrs["units"],
      f["ACTUATOR_STATE/xi"].shape if "xi" in f["ACTUATOR_STATE"] else None, "tracking", check_tracking(run, f),
      f["tracking/xi_error"].shape if "xi_error" in f["tracking"] else None)
)PY";

// Debian's python3 (with h5py) running `code` on `first` and `second`
// (sys.argv[1], [2]), with python/ and the Python tests' helpers importable.
RunResult exportPython(const std::string& code, const std::string& first, const std::string& second = "") {
  const std::string path =
      std::string(LAGRANGE_SOURCE_DIR) + "/python:" + LAGRANGE_SOURCE_DIR + "/python/tests";
  return shell("PYTHONPATH=" + quote(path) + " /usr/bin/python3 -c " + quote(code) + " " + quote(first) +
               " " + quote(second));
}

RunResult compareWithH5py(const std::string& run_dir, const std::string& h5) {
  return exportPython(kCompare, run_dir, h5);
}

// check_tracking on the log at sys.argv[1] and the file at sys.argv[2], then `then`.
RunResult checkTracking(const std::string& log, const std::string& h5, const std::string& then) {
  return exportPython(std::string("import sys, h5py, numpy, lagrange.log\n") + kTrackingCheck +
                          "\nrun = lagrange.log.load(sys.argv[1], numpy=False)\n"
                          "f = h5py.File(sys.argv[2], \"r\")\n"
                          "n = check_tracking(run, f)\n" +
                          then,
                      log, h5);
}

TEST(Export, H5pyReadsEverySampleBitForBitWithUnitsAndJointNames) {
  const std::string out = freshDir("export-rigid"), h5 = out + "/run.h5";
  ASSERT_EQ(runScenario(kConfigs + "/rigid_2dof.yaml", out, "-q --set duration=2").exit_code, 0);
  const RunResult e = lagrange("export " + quote(out) + " -o " + quote(h5));
  ASSERT_EQ(e.exit_code, 0) << e.output;
  EXPECT_NE(e.output.find("PLANT_TRUTH (2001 rows)"), std::string::npos) << e.output;
  const RunResult r = compareWithH5py(out, h5);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.rfind("4 ", 0), 0u) << r.output;  // four per-tick channels
  EXPECT_NE(r.output.find("['joint1', 'joint2'] rad None tracking 2001 None"), std::string::npos) << r.output;

  // An existing file stays unless --force; a missing run is named.
  const RunResult again = lagrange("export " + quote(out) + " -o " + quote(h5));
  EXPECT_EQ(again.exit_code, 2) << again.output;
  EXPECT_NE(again.output.find(h5 + " exists; expected a new file name (or --force to replace it)"),
            std::string::npos)
      << again.output;
  EXPECT_EQ(lagrange("export " + quote(out) + " -o " + quote(h5) + " --force -q").exit_code, 0);
  const std::string empty = freshDir("export-empty");
  std::filesystem::create_directories(empty);
  const RunResult none = lagrange("export " + quote(empty) + " -o " + quote(out + "/x.h5"));
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_NE(none.output.find("cannot read '" + empty +
                             "/run.lcm' (No such file or directory); expected a run directory (lagrange run "
                             "--out) or its run.lcm"),
            std::string::npos)
      << none.output;
  EXPECT_FALSE(std::filesystem::exists(out + "/x.h5"));
}

// A chain of order 2: the chain states are [samples, stages, joints].
TEST(Export, AnActuatorChainsStatesAreThreeDimensional) {
  const std::string out = freshDir("export-chain"), h5 = out + "/run.h5";
  ASSERT_EQ(runScenario(kConfigs + "/chain_m2.yaml", out, "-q --mode inproc --set duration=0.5").exit_code,
            0);
  ASSERT_EQ(lagrange("export " + quote(out) + " -o " + quote(h5) + " -q").exit_code, 0);
  const RunResult r = compareWithH5py(out, h5);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("(501, 2, 2) tracking 501 (501, 2, 2)"), std::string::npos) << r.output;
}

// Without -o the file goes into the run's folder (RUN/run.h5; a log named
// otherwise, beside it with .h5), and its /tracking is the controller's own
// q_error on a golden log (exact sensors: measured q is the true q).
TEST(Export, WithoutAFileNameItWritesIntoTheRunsFolderAndTracksAsTheController) {
  const std::string out = freshDir("export-default");
  std::filesystem::create_directories(out + "/run");
  std::filesystem::copy_file(kGoldenRigidLockstep, out + "/run/run.lcm");
  const RunResult e = lagrange("export " + quote(out + "/run"));
  ASSERT_EQ(e.exit_code, 0) << e.output;
  EXPECT_NE(e.output.find("wrote " + out + "/run/run.h5:"), std::string::npos) << e.output;
  EXPECT_NE(e.output.find("tracking (1001 rows)"), std::string::npos) << e.output;
  const RunResult r = checkTracking(out + "/run", out + "/run/run.h5", R"PY(
assert numpy.array_equal(f["tracking/q_error"][:], f["CONTROL_COMMAND/q_error"][:])
print("rows", n, f["tracking"].attrs["publish_rate"], f["tracking/t"][1])
)PY");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("rows 1001 1000.0 0.001"), std::string::npos) << r.output;
  // A log file of another name: beside it, .lcm replaced by .h5. Seven
  // joints: the norm is the correctly rounded one Python's math.fsum gives
  // (a plain sum of the squares differs in the last bit on 14 of its rows).
  std::filesystem::copy_file(kGoldenDir + "panda_theorem1_lockstep.lcm", out + "/panda.lcm");
  const RunResult beside = lagrange("export " + quote(out + "/panda.lcm") + " -q");
  ASSERT_EQ(beside.exit_code, 0) << beside.output;
  const RunResult panda =
      checkTracking(out + "/panda.lcm", out + "/panda.h5", "print(\"rows\", n, f[\"tracking/q\"].shape[1])");
  ASSERT_EQ(panda.exit_code, 0) << panda.output;
  EXPECT_NE(panda.output.find("rows 1001 7"), std::string::npos) << panda.output;
}

// A log made by hand (the Python tests' own message makers): ticks out of
// order, a tick of one channel only, a command damaged on the way, a command
// of another joint count -- /tracking joins, leaves out and counts as
// Run.tracking does.
TEST(Export, TrackingJoinsAndLeavesOutAsRunTrackingOnACraftedLog) {
  const std::string out = freshDir("export-crafted");
  std::filesystem::create_directories(out);
  const RunResult made = exportPython(R"PY(
import sys
from test_tracking import truth, command, write_log
write_log(sys.argv[1], [
    ("PLANT_TRUTH", truth(0, [1.0, -1.0])), ("CONTROL_COMMAND", command(0, [0.5, 0.5])),
    ("PLANT_TRUTH", truth(2, [0.25, 3.0])), ("PLANT_TRUTH", truth(1, [0.75, 0.0])),
    ("CONTROL_COMMAND", command(1, [0.75, -4.0])), ("CONTROL_COMMAND", command(2, [0.0, 3.0])),
    ("PLANT_TRUTH", truth(3, [9.0, 9.0])), ("CONTROL_COMMAND", command(5, [1.0, 1.0])),
    ("PLANT_TRUTH", truth(6, [1.0, 1.0])), ("CONTROL_COMMAND", command(6, [0.0, 0.0], corrupt=True)),
    ("PLANT_TRUTH", truth(7, [1.0, 1.0])), ("CONTROL_COMMAND", command(7, [0.0])),
    ("PLANT_TRUTH", truth(8, [0.1, 0.2])), ("CONTROL_COMMAND", command(8, [0.3, 0.7])),
    ("CONTROL_COMMAND", command(8, [5.0, 5.0])),
])
)PY",
                                      out);
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const RunResult e = lagrange("export " + quote(out));
  ASSERT_EQ(e.exit_code, 0) << e.output;
  EXPECT_NE(e.output.find("1 ticks whose PLANT_TRUTH.q and CONTROL_COMMAND.q_desired hold different numbers"),
            std::string::npos)
      << e.output;
  const RunResult r = checkTracking(out, out + "/run.h5",
                                    "print(\"rows\", n, run.tracking.unjoined, run.tracking.mismatched)");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // Ticks 0, 1, 2, 8; 3 and 6 (its command corrupt) truth only, 5 command only; 7 mismatched.
  EXPECT_NE(r.output.find("rows 4 {'PLANT_TRUTH': 2, 'CONTROL_COMMAND': 1} 1"), std::string::npos)
      << r.output;
}

// The files beside the log are read only when they are regular files of a
// sane size: a summary.json of 64 MiB (sparse: no run writes one) and a
// config.resolved.yaml that is a link to /dev/zero are left out, each named
// in a warning, and the log is exported from its own scenario.
TEST(Export, ARunFileThatIsNotARegularFileOrTooLargeIsLeftOutAndNamed) {
  const std::string out = freshDir("export-files"), h5 = out + "/run.h5";
  std::filesystem::create_directories(out);
  std::filesystem::copy_file(kGoldenRigidLockstep, out + "/run.lcm");
  { std::ofstream(out + "/summary.json") << "{}"; }
  std::filesystem::resize_file(out + "/summary.json", 64u << 20);
  std::filesystem::create_symlink("/dev/zero", out + "/config.resolved.yaml");
  const RunResult r = lagrange("export " + quote(out) + " -o " + quote(h5));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: '" + out +
                          "/summary.json' is larger than 64 MiB; expected the run's "
                          "summary.json of at most 16 MiB; left out of the export"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("warning: '" + out +
                          "/config.resolved.yaml' is a character device; expected the "
                          "run's resolved scenario (a regular file); left out of the export"),
            std::string::npos)
      << r.output;
  EXPECT_TRUE(std::filesystem::is_regular_file(h5));
}

}  // namespace
}  // namespace lagrange::testing
