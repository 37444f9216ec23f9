"""The example's two-link RK4 plant (examples/external_plant/two_link_plant.py),
but one step takes SECONDS of wall time: a plant that falls behind in
lockstep, which the logger must name while it lasts and count in
summary.json `answers.plant` (tests/integration/run_verdict_test.cpp).

    python3 -S slow_step_plant.py EXAMPLE_DIR STEP SECONDS [every]

With `every`, each step from STEP on takes SECONDS: a plant whose model
cannot hold the run's rate in realtime, whose block must name the timing
and the torque it held (tests/integration/run_verdict_test.cpp).
"""

import os
import sys
import time

example_dir, slow_step, seconds = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
every = sys.argv[4:] == ["every"]
sys.path.insert(0, example_dir)
sys.path.insert(0, os.path.join(example_dir, "..", "..", "python"))

import lagrange.external_plant  # noqa: E402

run = lagrange.external_plant.run


def run_with_a_slow_step(step, **options):
    calls = [0]

    def slow(t, u, dt):
        calls[0] += 1
        if calls[0] == slow_step or (every and calls[0] > slow_step):
            time.sleep(seconds)
        return step(t, u, dt)

    return run(slow, **options)


lagrange.external_plant.run = run_with_a_slow_step
import two_link_plant  # noqa: E402

sys.argv = ["two_link_plant.py"]
two_link_plant.main()
