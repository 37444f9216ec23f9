"""examples/notebooks/first_figure.ipynb executed as a student would run it
whole (Debian's jupyter-nbconvert with python3-ipykernel): every cell runs
without an error, the paper's controller and the baseline both ran and met
their metric, the sweep returned its nine rows typed as numbers, and both
figures were written as PNG files.

    LAGRANGE_BIN=build/bin/lagrange python3 -S tests/notebook_test.py
"""

import json
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
NOTEBOOK = os.path.join(ROOT, "examples", "notebooks", "first_figure.ipynb")


def check(condition, what):
    if not condition:
        sys.exit("FAIL: " + what)
    print("ok: " + what)


nbconvert = shutil.which("jupyter-nbconvert")
check(nbconvert is not None, "jupyter-nbconvert is installed (scripts/setup.sh: jupyter-nbconvert python3-ipykernel)")
work = tempfile.mkdtemp(prefix="lagrange-notebook-")
executed = os.path.join(work, "executed.ipynb")
env = dict(os.environ, LAGRANGE_NOTEBOOK_OUT=work, PYDEVD_DISABLE_FILE_VALIDATION="1")
# Run where a student opens it: the notebook's own folder is the kernel's working directory.
done = subprocess.run([nbconvert, "--to", "notebook", "--execute", "--ExecutePreprocessor.timeout=600",
                       NOTEBOOK, "--output", executed], cwd=os.path.dirname(NOTEBOOK), env=env,
                      stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
check(done.returncode == 0, "the notebook executes whole (exit %d):\n%s" % (done.returncode, done.stdout[-3000:]))

with open(executed) as f:
    cells = json.load(f)["cells"]
outputs = [o for c in cells if c["cell_type"] == "code" for o in c.get("outputs", [])]
check(not [o for o in outputs if o.get("output_type") == "error"], "no cell left an error")
text = "".join("".join(o.get("text", "")) for o in outputs if o.get("output_type") == "stream")
for name in ("theorem1", "pd_plus_differenced"):
    line = next((l for l in text.splitlines() if l.startswith(name + " ")), "")
    check(" verdict met " in line, "%s ran and met its metric: %r" % (name, line))
sweep_lines = [l for l in text.splitlines() if l.startswith("a = ")]
check(len(sweep_lines) == 9, "the sweep printed its nine rows: %d" % len(sweep_lines))
for figure in ("tracking_error.png", "convergence_map.png"):
    path = os.path.join(work, figure)
    check(os.path.isfile(path), "%s was written" % figure)
    with open(path, "rb") as f:
        head = f.read(8)
    check(head == b"\x89PNG\r\n\x1a\n" and os.path.getsize(path) > 10000,
          "%s is a PNG image, not empty (%d bytes)" % (figure, os.path.getsize(path)))
shutil.rmtree(work)
