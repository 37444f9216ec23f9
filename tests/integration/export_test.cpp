// `lagrange export RUN -o FILE` (tools/export/export.hpp): the HDF5 file read
// back by h5py (Debian's python3-h5py) holds every sample of the log, bit
// for bit as lagrange.log.load (python/, an independent reader of the LCM
// log) decodes it, with its units, joint names, scenario and summary; an
// existing file is not replaced without --force.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {
namespace {

// Compares every per-tick field of the run's log (lagrange.log, no numpy)
// with the HDF5 file (h5py), value for value; prints what it checked.
const char* kCompare = R"PY(
import json, sys, h5py, numpy, lagrange.log
run_dir, path = sys.argv[1], sys.argv[2]
run = lagrange.log.load(run_dir, numpy=False)
f = h5py.File(path, "r")
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
      f["ACTUATOR_STATE/xi"].shape if "xi" in f["ACTUATOR_STATE"] else None)
)PY";

RunResult compareWithH5py(const std::string& run_dir, const std::string& h5) {
  return shell("PYTHONPATH=" + quote(std::string(LAGRANGE_SOURCE_DIR) + "/python") + " /usr/bin/python3 -c " +
               quote(kCompare) + " " + quote(run_dir) + " " + quote(h5));
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
  EXPECT_NE(r.output.find("['joint1', 'joint2'] rad None"), std::string::npos) << r.output;

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
  EXPECT_NE(r.output.find("(501, 2, 2)"), std::string::npos) << r.output;
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
