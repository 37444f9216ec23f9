"""The built lagrange program the tests that run it drive: PROGRAM (None when
lagrange.program() finds none) and NO_PROGRAM (where it looked), with the
checkout's python/ first on sys.path. One place for test_sweep_rows and
test_tune."""

import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "python"))

import lagrange  # noqa: E402
import lagrange.programs  # noqa: E402

try:
    PROGRAM, NO_PROGRAM = lagrange.programs.program(), ""
except lagrange.LagrangeError as e:
    PROGRAM, NO_PROGRAM = None, str(e)
