"""A baseline from Python and the command line (issue #54 items 1 and 4):
lagrange.run's keywords and `lagrange run --set` that change a section's type
replace the section whole, in any order; config.resolved.yaml holds the new
section only; a key of another type, a near miss (controller__Kd) and a
guessed key (controller__rate) are refused naming what was meant. Runs the
built program (LAGRANGE_BIN, else `lagrange` on PATH, else this checkout's
build/bin/lagrange) in process mode, 0.5 s of simulated time each.

    PYTHONPATH=python python3 -S -m unittest python/tests/test_type_switch.py
"""

import os
import shutil
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "python"))

import lagrange  # noqa: E402
import lagrange.programs  # noqa: E402

SCENARIO = os.path.join(ROOT, "configs", "rigid_2dof.yaml")
# Short runs: 0.5 s of simulated time, judged at 0.5 s.
SHORT = {"duration": 0.5, "metrics__convergence_deadline": 0.5}


def resolved_section(out, section):
    """The lines of `section` in OUT/config.resolved.yaml: its key lines, as
    the program writes them (one key a line, two spaces in)."""
    lines, inside = [], False
    with open(os.path.join(out, "config.resolved.yaml")) as f:
        for line in f:
            if not line.startswith(" "):
                inside = line.rstrip() == section + ":"
            elif inside and line.startswith("  ") and not line.startswith("   "):
                lines.append(line.strip().split(":")[0])
    return lines


class TypeSwitch(unittest.TestCase):
    def setUp(self):
        self.program = lagrange.programs.program()  # LagrangeError, naming where it looked, when there is none
        self.work = tempfile.mkdtemp(prefix="lagrange-type-switch-")

    def tearDown(self):
        shutil.rmtree(self.work)

    def test_a_baseline_from_python_keywords(self):
        out = os.path.join(self.work, "pd")
        run = lagrange.run(SCENARIO, out=out, mode="inproc", controller__type="pd_plus_differenced",
                           controller__kp=[150, 10], controller__kd=[15, 1], **SHORT)
        self.assertEqual(run.summary["status"], "completed")
        self.assertEqual(run.scenario["controller"],
                         {"type": "pd_plus_differenced", "kp": [150.0, 10.0], "kd": [15.0, 1.0]})
        self.assertEqual(sorted(resolved_section(out, "controller")), ["kd", "kp", "type"])

    def test_the_same_with_set_in_the_other_order(self):
        out = os.path.join(self.work, "cli")
        done = subprocess.run([self.program, "run", SCENARIO, "--out", out, "--quiet", "--mode", "inproc",
                               "--set", "duration=0.5", "--set", "metrics.convergence_deadline=0.5",
                               "--set", "controller.kd=[15, 1]", "--set", "controller.kp=[150, 10]",
                               "--set", "controller.type=pd_plus_differenced"],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        self.assertEqual(done.returncode, 0, done.stdout)
        self.assertEqual(sorted(resolved_section(out, "controller")), ["kd", "kp", "type"])

    def test_a_sine_reference_drops_alpha(self):
        run = lagrange.run(SCENARIO, out=os.path.join(self.work, "sine"), mode="inproc", reference__type="sine",
                           reference__offset=[0.5, 1.0], reference__amplitude=0.2, reference__frequency=3.0,
                           **SHORT)
        self.assertEqual(run.scenario["reference"]["type"], "sine")
        self.assertNotIn("alpha", run.scenario["reference"])

    def refusal(self, **overrides):
        with self.assertRaises(lagrange.LagrangeError) as caught:
            lagrange.run(SCENARIO, out=os.path.join(self.work, "refused"), mode="inproc", **overrides)
        self.assertEqual(caught.exception.exit_code, 2, str(caught.exception))
        return str(caught.exception)

    def test_a_key_of_another_type_is_refused_naming_the_type(self):
        error = self.refusal(controller__type="pd_plus_differenced", controller__kp=[150, 10],
                             controller__kd=[15, 1], controller__a=[50, 50])
        self.assertIn("controller.a: unknown key", error)
        self.assertIn("expected one of: kd, kp, type (the keys of controller type pd_plus_differenced)", error)

    def test_a_near_miss_and_a_guessed_key_are_named(self):
        # Named by the keyword the script wrote, not the --set it became.
        self.assertIn("controller.Kd: unknown key (from the keyword controller__Kd=[15, 1]); did you mean kd?",
                      self.refusal(controller__Kd=[15, 1]))
        self.assertIn("controller.rate: unknown key (from the keyword controller__rate=200); the control rate "
                      "is plant.publish_rate [Hz]", self.refusal(controller__rate=200))
        self.assertNotIn("--set", self.refusal(controller__rate=200))


if __name__ == "__main__":
    unittest.main()
