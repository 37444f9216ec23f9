"""Run.tracking (issue #54): the true tracking error q - q_d per tick, from
PLANT_TRUTH.q and CONTROL_COMMAND.q_desired joined by header.tick, with
t = tick / plant.publish_rate of the run's scenario. Each test writes its run
folder itself, as test_reader_guards.py does; one reads a golden log.

    PYTHONPATH=python python3 -S -m unittest discover -s python/tests
"""

import json
import math
import os
import sys
import tempfile
import unittest
from unittest import mock

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "python"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import lagrange  # noqa: E402
import lagrange.contract  # noqa: E402
import lagrange.log  # noqa: E402
from test_reader_guards import GOLDEN, event, golden_scenario  # noqa: E402

try:
    import numpy
except ImportError:
    numpy = None

# A sim_time no tick of a 1 kHz run has: t must never come from it.
WRONG_SIM_TIME = 99.0


def header(tick, publisher):
    h = lagrange.header_t()
    h.tick, h.sim_time, h.run_id, h.publisher = tick, WRONG_SIM_TIME, 7, publisher
    return h


def truth(tick, q):
    """A PLANT_TRUTH of `tick` holding the true angles `q`, sealed."""
    m = lagrange.plant_truth_t()
    m.header = header(tick, "plant")
    n = len(q)
    m.num_joints, m.q, m.qdot, m.tau_applied = n, list(q), [0.0] * n, [0.0] * n
    return lagrange.contract.seal(m).encode()


def command(tick, q_desired, corrupt=False):
    """A CONTROL_COMMAND of `tick` whose reference is `q_desired`, sealed
    (with `corrupt`, one byte of q_desired changed after sealing)."""
    m = lagrange.control_command_t()
    m.header = header(tick, "controller")
    n = len(q_desired)
    m.input_position_tick, m.input_actuator_tick, m.input_motor_tick = tick, -1, -1
    m.num_joints, m.u, m.q_desired = n, [1.0] * n, list(q_desired)
    m.q_error, m.theta, m.filter_state, m.chain_order, m.xi_error = [0.0] * n, [0.0] * n, [0.0] * n, 0, []
    data = lagrange.contract.seal(m).encode()
    if corrupt:  # q_desired's last byte (before q_error, theta, filter_state, chain_order): still decodes
        at = len(data) - 3 * 8 * n - 4 - 1
        data = data[:at] + bytes([data[at] ^ 1]) + data[at + 1:]
    return data


def write_log(folder, events, scenario=True):
    """run.lcm in `folder`: the golden SCENARIO (1 s at 1 kHz, two joints)
    when `scenario`, then `events` ((channel, data), in that order)."""
    with open(os.path.join(folder, "run.lcm"), "wb") as f:
        if scenario:
            f.write(event("SCENARIO", golden_scenario()))
        for n, (channel, data) in enumerate(events):
            f.write(event(channel, data, n + 1))


class Tracking(unittest.TestCase):
    def folder(self):
        d = tempfile.TemporaryDirectory()
        self.addCleanup(d.cleanup)
        return d.name

    def test_joins_by_tick_and_counts_a_tick_of_one_channel_only(self):
        d = self.folder()
        write_log(d, [
            ("PLANT_TRUTH", truth(0, [1.0, -1.0])),
            ("CONTROL_COMMAND", command(0, [0.5, 0.5])),
            ("PLANT_TRUTH", truth(2, [0.25, 3.0])),       # tick 2 before tick 1: rows come out by tick
            ("PLANT_TRUTH", truth(1, [0.75, 0.0])),
            ("CONTROL_COMMAND", command(1, [0.75, -4.0])),
            ("CONTROL_COMMAND", command(2, [0.0, 3.0])),
            ("PLANT_TRUTH", truth(3, [9.0, 9.0])),        # tick 3: no command
            ("CONTROL_COMMAND", command(5, [1.0, 1.0])),  # tick 5: no truth
        ])
        tr = lagrange.log.load(d, numpy=False).tracking
        self.assertEqual(tr["tick"], [0, 1, 2])
        self.assertEqual(tr["t"], [0.0, 0.001, 0.002])  # tick / 1000 Hz, not the messages' sim_time
        self.assertEqual(tr["q_error"], [[0.5, -1.5], [0.0, 4.0], [0.25, 0.0]])
        self.assertEqual(tr["error_norm"], [math.hypot(0.5, -1.5), 4.0, 0.25])
        self.assertEqual(tr.unjoined, {"PLANT_TRUTH": 1, "CONTROL_COMMAND": 1})
        self.assertEqual(tr.mismatched, 0)
        self.assertEqual(tr.publish_rate, 1000.0)
        self.assertEqual(set(tr), {"tick", "t", "q", "q_desired", "q_error", "error_norm"})

    def test_a_command_left_out_as_corrupt_leaves_its_tick_unjoined(self):
        d = self.folder()
        write_log(d, [
            ("PLANT_TRUTH", truth(0, [1.0, 1.0])),
            ("CONTROL_COMMAND", command(0, [0.0, 0.0])),
            ("PLANT_TRUTH", truth(1, [1.0, 1.0])),
            ("CONTROL_COMMAND", command(1, [0.0, 0.0], corrupt=True)),
        ])
        run = lagrange.log.load(d, numpy=False)
        self.assertEqual(run.corrupt, {"CONTROL_COMMAND": 1})
        self.assertEqual(run.tracking["tick"], [0])
        self.assertEqual(run.tracking.unjoined, {"PLANT_TRUTH": 1, "CONTROL_COMMAND": 0})

    def test_rows_of_different_joint_counts_are_not_subtracted(self):
        d = self.folder()
        write_log(d, [
            ("PLANT_TRUTH", truth(0, [1.0, 1.0])),
            ("CONTROL_COMMAND", command(0, [0.0])),  # one joint against two
            ("PLANT_TRUTH", truth(1, [1.0, 1.0])),
            ("CONTROL_COMMAND", command(1, [1.0, 0.0])),
        ])
        tr = lagrange.log.load(d, numpy=False).tracking
        self.assertEqual(tr["tick"], [1])
        self.assertEqual(tr["q_error"], [[0.0, 1.0]])
        self.assertEqual(tr.mismatched, 1)
        self.assertEqual(tr.unjoined, {"PLANT_TRUTH": 0, "CONTROL_COMMAND": 0})

    def test_the_rate_comes_from_the_resolved_scenario_without_a_scenario_in_the_log(self):
        d = self.folder()
        write_log(d, [("PLANT_TRUTH", truth(4, [1.0, 0.0])), ("CONTROL_COMMAND", command(4, [0.0, 0.0]))],
                  scenario=False)
        with open(os.path.join(d, "config.resolved.json"), "w") as f:
            json.dump({"plant": {"publish_rate": 500}}, f)
        tr = lagrange.log.load(d, numpy=False).tracking
        self.assertEqual((tr["tick"], tr["t"], tr.publish_rate), ([4], [0.008], 500.0))

    def test_without_a_rate_t_is_none_and_the_rest_is_there(self):
        d = self.folder()
        write_log(d, [("PLANT_TRUTH", truth(4, [1.0, 0.0])), ("CONTROL_COMMAND", command(4, [0.0, 0.0]))],
                  scenario=False)
        tr = lagrange.log.load(d, numpy=False).tracking
        self.assertIsNone(tr["t"])
        self.assertIsNone(tr.publish_rate)
        self.assertEqual((tr["tick"], tr["q_error"], tr["error_norm"]), ([4], [[1.0, 0.0]], [1.0]))

    def test_a_log_without_either_channel_has_empty_columns(self):
        d = self.folder()
        write_log(d, [("PLANT_TRUTH", truth(0, [1.0, 0.0]))])
        tr = lagrange.log.load(d, numpy=False).tracking
        self.assertEqual((tr["tick"], tr["q_error"], tr["error_norm"], tr["t"]), ([], [], [], []))
        self.assertEqual(tr.unjoined, {"PLANT_TRUTH": 1, "CONTROL_COMMAND": 0})

    def test_a_golden_run_is_what_its_controller_computed(self):
        # rigid_2dof in lockstep with exact sensors: the controller's own
        # q_error (measured q - q_d, computed in C++) is the truth's, bit for bit.
        run = lagrange.log.load(os.path.join(GOLDEN, "rigid_2dof_lockstep.lcm"), numpy=False)
        tr = run.tracking
        cmd = run.channels["CONTROL_COMMAND"]
        self.assertEqual(len(tr["tick"]), 1001)
        self.assertEqual(tr.unjoined, {"PLANT_TRUTH": 0, "CONTROL_COMMAND": 0})
        self.assertEqual(tr["tick"], sorted(cmd["header.tick"]))
        self.assertEqual(tr["q_error"], [list(row) for row in cmd["q_error"]])
        self.assertEqual(tr["t"], [tick * (1.0 / 1000.0) for tick in tr["tick"]])
        self.assertLess(tr["error_norm"][-1], 1e-3)
        # q and q_d beside the error: the truth's and the command's rows of each tick.
        truth_row = {tick: k for k, tick in enumerate(run.channels["PLANT_TRUTH"]["header.tick"])}
        cmd_row = {tick: k for k, tick in enumerate(cmd["header.tick"])}
        for k in (0, 500, 1000):
            tick = tr["tick"][k]
            self.assertEqual(tr["q"][k], list(run.channels["PLANT_TRUTH"]["q"][truth_row[tick]]))
            self.assertEqual(tr["q_desired"][k], list(cmd["q_desired"][cmd_row[tick]]))
            self.assertEqual(tr["q_error"][k], [a - d for a, d in zip(tr["q"][k], tr["q_desired"][k])])
        self.assertNotIn("xi_error", tr)  # theorem1 has no chain

    def test_a_chain_run_gives_its_stage_errors(self):
        # chain_m2 (the cascade behind two integrators): xi_error per tick, one row per stage.
        run = lagrange.log.load(os.path.join(GOLDEN, "chain_m2_lockstep.lcm"), numpy=False)
        tr = run.tracking
        cmd = run.channels["CONTROL_COMMAND"]
        self.assertEqual(len(tr["xi_error"]), len(tr["tick"]))
        row = {tick: k for k, tick in enumerate(cmd["header.tick"])}
        last = tr["tick"][-1]
        self.assertEqual(len(tr["xi_error"][-1]), 2)
        self.assertEqual(tr["xi_error"][-1], [list(stage) for stage in cmd["xi_error"][row[last]]])

    @unittest.skipIf(numpy is None, "numpy is not installed (python3 -S does not see Debian's python3-numpy)")
    def test_with_numpy_the_columns_are_arrays(self):
        run = lagrange.log.load(os.path.join(GOLDEN, "rigid_2dof_lockstep.lcm"), numpy=True)
        tr = run.tracking
        self.assertEqual(tr["q_error"].shape, (1001, 2))
        self.assertEqual(tr["tick"].dtype, numpy.int64)
        self.assertTrue(numpy.array_equal(tr["q_error"], run.channels["CONTROL_COMMAND"]["q_error"]))
        self.assertTrue(numpy.array_equal(tr["error_norm"], numpy.linalg.norm(tr["q_error"], axis=1)))

    def test_numpy_asked_for_but_missing_names_the_debian_package(self):
        with mock.patch.dict(sys.modules, {"numpy": None}):  # import numpy now fails
            with self.assertRaises(ModuleNotFoundError) as caught:
                lagrange.log.load(os.path.join(GOLDEN, "rigid_2dof_lockstep.lcm"), numpy=True)
            self.assertIn("python3-numpy", str(caught.exception))
            self.assertEqual(caught.exception.name, "numpy")
            # numpy=None still reads the log, into lists
            run = lagrange.log.load(os.path.join(GOLDEN, "rigid_2dof_lockstep.lcm"))
            self.assertIsInstance(run.tracking["t"], list)


if __name__ == "__main__":
    unittest.main()
