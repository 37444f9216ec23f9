"""lagrange.sweep's rows hold each axis value as the scenario reads it (issue
#54 item 3): a sweep over a vector gain gives controller.kd as a list of
floats, not the text "[5.0, 0.4]", and sweep.csv a column per joint. A tiny
sweep (two runs of 0.2 s, in process) through the built lagrange program;
skipped when there is none (lagrange.program() names where it looked).

    PYTHONPATH=python python3 -S -m unittest discover -s python/tests
"""

import csv
import os
import shutil
import sys
import tempfile
import unittest

from built_program import NO_PROGRAM, PROGRAM, ROOT  # noqa: E402  (python/ on sys.path first)

import lagrange  # noqa: E402


@unittest.skipIf(PROGRAM is None, "no lagrange program to run the sweep: %s" % NO_PROGRAM)
class SweepRows(unittest.TestCase):
    def setUp(self):
        self.work = tempfile.mkdtemp(prefix="lagrange-python-sweep-rows-")
        self.addCleanup(shutil.rmtree, self.work)

    def test_a_vector_axis_gives_a_list_of_floats_per_row_and_a_csv_column_per_joint(self):
        spec = os.path.join(self.work, "kd.yaml")
        with open(spec, "w") as f:
            f.write("scenario: %s\nset: {duration: 0.2}\naxes:\n  - key: controller.kd\n"
                    "    values: [[5.0, 0.4], [20, 2]]\n" % os.path.join(ROOT, "configs", "rigid_2dof.yaml"))
        out = os.path.join(self.work, "out")
        rows = lagrange.sweep(spec, out=out, jobs=1)
        self.assertEqual([r["index"] for r in rows], [0, 1])
        self.assertEqual([r["controller.kd"] for r in rows], [[5.0, 0.4], [20.0, 2.0]])
        for r in rows:
            self.assertTrue(all(isinstance(k, float) for k in r["controller.kd"]), r["controller.kd"])
        with open(os.path.join(out, "sweep.csv"), newline="") as f:
            table = list(csv.DictReader(f))
        self.assertNotIn("controller.kd", table[0])
        self.assertEqual([(float(r["controller.kd[0]"]), float(r["controller.kd[1]"])) for r in table],
                         [(5.0, 0.4), (20.0, 2.0)])


if __name__ == "__main__":
    unittest.main()
