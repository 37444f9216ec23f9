"""A plant from outside that lies about the run's clock and ticks: the
example's two-link RK4 plant (examples/external_plant/two_link_plant.py)
with one lie, for the tests of "the run's clock and ticks are the logger's"
(tests/integration/hostile_plant_test.cpp). Every message is properly
signed: the lies are in what the plant says, not in how.

    python3 -S hostile_plant.py EXAMPLE_DIR LIE [N]

LIE:
  half_time      stamps sim_time at half its tick's time (tick / rate / 2):
                 a late run made to look quick
  past_end N     publishes N ticks past the run's last one (realtime)
  finish_early N says "finished" after tick N and exits 0 (lockstep)
  jump N         serves ticks 0..N, then sends the run's last tick and
                 says "finished" (lockstep): the run's length without its ticks
  vanish N       serves ticks 0..N and exits 0 without a word (lockstep)
  huge N         from tick N on says q = 1e308 (finite, past any arm's range)
  nan_truth N    from tick N on says NaN in PLANT_TRUTH's qdot only
"""

import os
import sys

example_dir, lie = sys.argv[1], sys.argv[2]
n = int(sys.argv[3]) if len(sys.argv) > 3 else 0
sys.path.insert(0, example_dir)
sys.path.insert(0, os.path.join(example_dir, "..", "..", "python"))

import lagrange.external_plant  # noqa: E402

Plant = lagrange.external_plant.Plant
honest_init, honest_publish, honest_finish = Plant.__init__, Plant._publish, Plant._finish


def lying_init(self, *args, **kwargs):
    honest_init(self, *args, **kwargs)
    self.run_last_tick = self.last_tick
    if lie == "past_end":
        self.last_tick += n
    elif lie in ("finish_early", "jump", "vanish"):
        self.last_tick = n


def half_time_publish(self, channel, msg, tick, sim_time):
    if channel in ("PLANT_POSITION", "PLANT_TRUTH"):
        sim_time = sim_time / 2
    return honest_publish(self, channel, msg, tick, sim_time)


def jumping_finish(self, message, loop=None):
    # Ticks N+1 .. last never happened: the last one is sent as if they had.
    self.last_tick = self.run_last_tick
    self._send(self._sample(self.last_tick, [0.0] * self.joints, lagrange.external_plant.TORQUE_ZERO, -1))
    return honest_finish(self, message, loop)


def lying_sample(self, k, tau, source, input_tick):
    sample = honest_sample(self, k, tau, source, input_tick)
    if k >= n:
        _, _, p, tr = sample
        if lie == "huge":
            p.q = [1e308] * len(p.q)
            tr.q = [1e308] * len(tr.q)
        else:
            tr.qdot = [float("nan")] * len(tr.qdot)
    return sample


honest_sample = Plant._sample


def silent_finish(self, message, loop=None):
    return 0  # no "finished": the program just ends


LIES = ("half_time", "past_end", "finish_early", "jump", "vanish", "huge", "nan_truth")
if lie not in LIES:
    sys.exit("hostile_plant.py: unknown lie %r; expected one of %s" % (lie, ", ".join(LIES)))
Plant.__init__ = lying_init
if lie == "half_time":
    Plant._publish = half_time_publish
if lie == "jump":
    Plant._finish = jumping_finish
if lie == "vanish":
    Plant._finish = silent_finish
if lie in ("huge", "nan_truth"):
    Plant._sample = lying_sample

import two_link_plant  # noqa: E402

sys.argv = ["two_link_plant.py"]
two_link_plant.main()
