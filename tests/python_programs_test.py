"""lagrange.run and lagrange.sweep from a plain script (python3 -S: no
site-packages): the notebook wrappers over the installed programs return
what lagrange.log.load returns, and name what went wrong.

    LAGRANGE_BIN=build/bin/lagrange python3 -S tests/python_programs_test.py
"""

import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
import lagrange  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def check(condition, what):
    if not condition:
        sys.exit("FAIL: " + what)
    print("ok: " + what)


work = tempfile.mkdtemp(prefix="lagrange-python-programs-")
run = lagrange.run(os.path.join(ROOT, "configs/rigid_2dof.yaml"), out=os.path.join(work, "run"), mode="inproc",
                   duration=1.0, metrics__convergence_deadline=1.0, controller__kp=[150.0, 10.0])
check(run.summary["status"] == "completed", "lagrange.run returns the run's summary")
check(len(run.channels["PLANT_TRUTH"]["q"]) == 1001, "... and its columns: 1001 samples of a 1 s run at 1 kHz")
check(run.scenario["duration"] == 1.0 and run.scenario["mode"] == "inproc", "... with the overrides applied")
check(run.verdict is run.summary["verdict"] and run.verdict["tracking"] == "met" and run.verdict["met"] is True
      and run.verdict["reasons"] == [], "... and its verdict as summary.json has it: %r" % (run.verdict,))

try:
    lagrange.run(os.path.join(ROOT, "configs/rigid_2dof.yaml"), out=os.path.join(work, "bad"), controller__kp=-1)
    check(False, "a bad override is refused")
except lagrange.LagrangeError as e:
    check(e.exit_code == 2 and "controller.kp" in str(e), "a bad override is refused naming the key: %s" % e)

sweep_file = os.path.join(work, "tiny.yaml")
with open(sweep_file, "w") as f:
    f.write("scenario: %s\nseed: 1\naxes:\n  - key: controller.kd\n    values: [[15.0, 1.0], [20.0, 2.0]]\n"
            "set: {duration: 1.0, metrics.convergence_deadline: 1.0}\n" % os.path.join(ROOT, "configs/rigid_2dof.yaml"))
rows = lagrange.sweep(sweep_file, out=os.path.join(work, "sweep"), jobs=1)
check([r["index"] for r in rows] == [0, 1], "lagrange.sweep returns one row per run, in order")
check(all(r["status"] == "completed" for r in rows), "... each with its status")
check(all(r["verdict"] in ("met", "NOT met") for r in rows), "... and its run's verdict: %r" % ([r["verdict"] for r in rows],))

os.environ["LAGRANGE_BIN"] = os.path.join(work, "no-such-lagrange")
try:
    lagrange.run(os.path.join(ROOT, "configs/rigid_2dof.yaml"))
    check(False, "a missing program is named")
except lagrange.LagrangeError as e:
    check("LAGRANGE_BIN=" in str(e) and "not an executable file" in str(e), "a missing program is named: %s" % e)

import shutil  # noqa: E402

shutil.rmtree(work)
