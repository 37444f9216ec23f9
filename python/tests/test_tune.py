"""lagrange.tune (docs/tuning.md): a tune of a few evaluations of the 2-joint
arm's short runs through the built lagrange program returns the best gains
and every evaluation; a rate no gains can meet raises LagrangeError naming
it. Skipped when there is no program (lagrange.program() names where it looked).

    PYTHONPATH=python python3 -S -m unittest discover -s python/tests
"""

import os
import shutil
import sys
import tempfile
import unittest

from built_program import NO_PROGRAM, PROGRAM, ROOT  # noqa: E402  (python/ on sys.path first)

import lagrange  # noqa: E402

SCENARIO = os.path.join(ROOT, "configs", "rigid_2dof.yaml")
SHORT = {"duration": 2.0, "plant__physics_step": 1e-4, "metrics__convergence_deadline": 1.5}


@unittest.skipIf(PROGRAM is None, "no lagrange program to tune with: %s" % NO_PROGRAM)
class Tune(unittest.TestCase):
    def setUp(self):
        self.work = tempfile.mkdtemp(prefix="lagrange-python-tune-")
        self.addCleanup(shutil.rmtree, self.work)

    def test_returns_the_best_that_passed_and_every_evaluation_in_order(self):
        out = os.path.join(self.work, "tuned")
        best, evaluations = lagrange.tune(SCENARIO, out=out, evaluations=5, jobs=2, args=["--global", "4"],
                                          **SHORT)
        self.assertTrue(best["feasible"])
        self.assertEqual(best["sampled_verdict"], "adequate")
        self.assertEqual(sorted(best["gains"]), ["a", "b", "kd", "kp"])
        self.assertEqual(len(best["gains"]["kp"]), 2)
        self.assertEqual(evaluations[0]["phase"], "start")
        self.assertEqual(evaluations[0]["gains"]["kp"], [150.0, 10.0])
        self.assertLessEqual(best["convergence_time"], evaluations[0]["convergence_time"])
        self.assertIn(best["convergence_time"], [e["convergence_time"] for e in evaluations if e["feasible"]])
        self.assertTrue(os.path.isfile(os.path.join(out, "tuned.yaml")))

    def test_a_rate_no_gains_meet_raises_naming_it(self):
        with self.assertRaises(lagrange.LagrangeError) as caught:
            lagrange.tune(SCENARIO, out=os.path.join(self.work, "slow"), evaluations=4, jobs=2,
                          plant__publish_rate=20, args=["--global", "3"], **SHORT)
        self.assertEqual(caught.exception.exit_code, 1)
        self.assertIn("20 Hz", str(caught.exception))
        self.assertIn("would suffice", str(caught.exception))

    def test_a_budget_that_is_no_number_is_refused_before_anything_runs(self):
        with self.assertRaises(lagrange.LagrangeError):
            lagrange.tune(SCENARIO, out=os.path.join(self.work, "never"), evaluations="many")
        self.assertFalse(os.path.exists(os.path.join(self.work, "never")))


if __name__ == "__main__":
    unittest.main()
