"""lagrange.external_plant under load and in lockstep (issue #52, items 6-8),
in process: the plant serves on LCM's in-process memq:// bus, and this test
plays the actuator and the logger on the same bus. No timing is asserted:
a step() that sleeps two periods makes the loop late for certain, and what
is asserted is what the plant did about it.

    python3 -S tests/python_plant_helpers_test.py
"""

import json
import math
import os
import sys
import tempfile
import time
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))

import lagrange  # noqa: E402
import lagrange.contract  # noqa: E402
import lagrange.external_plant as P  # noqa: E402

KEY = lagrange.contract.Key(b"\x5a" * 32)
RUN_ID = 7


def scenario(mode, rate=1000.0, duration=0.2, retransmit=0.02, max_torque_age=2):
    return {"mode": mode, "duration": duration, "plant": {"publish_rate": rate},
            "lockstep": {"retransmit_timeout": retransmit, "logger_window": 50, "stall_timeout": 5.0},
            "realtime": {"max_torque_age": max_torque_age, "hold_periods": 0, "stale_torque": "zero"},
            "initial_state": {"q": [0.0, 0.0], "qdot": [0.0, 0.0]}}


def header(tick, publisher):
    h = lagrange.header_t()
    h.tick, h.sim_time, h.run_id, h.publisher = tick, tick * 1e-3, RUN_ID, publisher
    h.publish_utime = time.monotonic_ns() // 1000
    return h


def status(process, last_tick):
    s = lagrange.status_t()
    s.header = header(max(last_tick, 0), process)
    s.process, s.state, s.last_tick, s.message = process, "running", last_tick, ""
    s.tracking_error = 0.0
    s.num_channels, s.channels = 0, []
    s.loop = lagrange.loop_stats_t()
    s.loop.scheduler = ""
    return lagrange.contract.seal(s)


def actuator_state(tick, tau):
    a = lagrange.actuator_state_t()
    a.header = header(tick, "actuator")
    a.input_command_tick = tick
    a.num_joints, a.order, a.torque_steps = len(tau), 0, 1
    a.u_commanded, a.tau_applied, a.saturated, a.xi = list(tau), [list(tau)], [False] * len(tau), []
    return lagrange.contract.seal(a)


def torque_of(tick):
    return [float(tick), -float(tick)]  # tells which tick's answer was applied


class FakeRun:
    """The actuator and the logger on the plant's own memq:// bus: every
    position is answered with its tick's ACTUATOR_STATE (but for the ticks
    in `late`, whose first copy goes unanswered: the re-sent one is), and
    every PLANT_TRUTH confirmed by the logger's STATUS."""

    def __init__(self, mode, step, watchdog_periods=None, brake=None, late=(), **kw):
        self.dir = tempfile.TemporaryDirectory()
        key_file = os.path.join(self.dir.name, "run.key")
        with open(key_file, "w") as f:
            f.write("5a" * 32 + "\n")
        config = os.path.join(self.dir.name, "config.resolved.json")
        with open(config, "w") as f:
            json.dump(scenario(mode, **kw), f)
        env = {"LAGRANGE_LCM_URL": "memq://", "LAGRANGE_RUN_ID": str(RUN_ID), "LAGRANGE_KEY_FILE": key_file,
               "LAGRANGE_JOINTS": "2", "LAGRANGE_MODE": mode, "LAGRANGE_CONFIG_JSON": config}
        self.plant = P.Plant(step, watchdog_periods=watchdog_periods, brake=brake, environ=env)
        self.late = set(late)
        self.copies = {}  # tick -> positions seen
        self.truth = []  # PLANT_TRUTH as published
        self.statuses = []  # (state, loop, message) of the plant's STATUS
        lc = self.plant.lcm
        lc.subscribe("PLANT_POSITION", self._on_position)
        lc.subscribe("PLANT_TRUTH", self._on_truth)
        publish_status = self.plant.publish_status
        self.plant.publish_status = lambda state, last_tick, message="", loop=None: (
            self.statuses.append((state, loop, message)), publish_status(state, last_tick, message, loop))
        for process in ("logger", "controller", "actuator"):  # a realtime plant starts once it heard them
            self.publish("STATUS", status(process, -1))

    def close(self):
        self.plant.lcm.close()
        self.dir.cleanup()

    def handle_all(self):
        while self.plant.lcm.handle_timeout(0) > 0:
            pass

    def publish(self, channel, msg):
        self.plant.lcm.publish(channel, KEY.sign(msg.encode()))

    def _on_position(self, _channel, data):
        p = lagrange.plant_position_t.decode(KEY.authenticate(data))
        k = p.header.tick
        self.copies[k] = self.copies.get(k, 0) + 1
        if k in self.late and self.copies[k] == 1:
            return  # answered only when re-sent: late by lockstep.retransmit_timeout
        self.publish("ACTUATOR_STATE", actuator_state(k, torque_of(k)))

    def _on_truth(self, _channel, data):
        t = lagrange.plant_truth_t.decode(KEY.authenticate(data))
        self.truth.append(t)
        self.publish("STATUS", status("logger", t.header.tick))


def sleeping_step(seconds):
    def step(t, u, dt):
        time.sleep(seconds)
        return [0.0, 0.0], [0.0, 0.0]
    return step


class BehindSchedule(unittest.TestCase):
    """Item 7: a realtime plant whose step() costs two periods still reads
    every answer and applies the newest fresh torque; the lateness is counted."""

    def test_a_plant_two_periods_late_every_tick_still_applies_each_fresh_torque(self):
        run = FakeRun("realtime", sleeping_step(2e-3), rate=1000.0, duration=0.1)
        self.addCleanup(run.close)
        self.assertEqual(run.plant.serve(), 0)
        run.handle_all()  # the last tick's PLANT_TRUTH, on the bus
        state, loop, message = run.statuses[-1]
        self.assertEqual(state, "finished")
        ticks = int(round(0.1 * 1000))
        # The fault happened: every period after the first ran past its deadline.
        self.assertGreaterEqual(loop.deadline_misses, ticks // 2, "step() sleeps 2 periods: the loop must be late")
        self.assertGreaterEqual(loop.longest_miss_run, ticks // 2)
        # ... and the rule held: each period's torque is the answer to the tick
        # just published, read from the socket although the period was over.
        self.assertEqual(len(run.truth), ticks + 1)
        for t in run.truth[1:]:
            k = t.header.tick
            self.assertEqual((t.torque_source, t.input_actuator_tick, list(t.tau_applied)),
                             (P.TORQUE_COMMANDED, k - 1, torque_of(k - 1)),
                             "tick %d: the fresh torque of tick %d applied" % (k, k - 1))
        self.assertEqual((loop.torque_zeroed, loop.torque_held, loop.missing_inputs), (0, 0, 0))
        self.assertEqual(message, "torque_held=0 torque_zeroed=0")
        # Latency and input age measured (finite), as the built-in plant's.
        for name in ("latency_p50", "latency_max", "input_age_p50", "input_age_max"):
            self.assertTrue(math.isfinite(getattr(loop, name)) and getattr(loop, name) >= 0.0, name)

    def test_the_drain_reads_past_the_deadline_but_stops_a_flood(self):
        run = FakeRun("realtime", sleeping_step(0.0))
        self.addCleanup(run.close)
        run.handle_all()  # the peers' STATUS
        forged = lagrange.contract.Key(bytes(32))
        for i in range(P.DRAIN_MAX + 500):  # a flood of forged datagrams, each refused by its MAC
            run.plant.lcm.publish("ACTUATOR_STATE", forged.sign(actuator_state(i, [1.0, 1.0]).encode()))
        past = time.monotonic() - 1.0
        self.assertEqual(run.plant._drain(until=past), P.DRAIN_LATE, "late: a bounded read, not none")
        self.assertEqual(run.plant._drain(until=time.monotonic() + 60.0), P.DRAIN_MAX, "never more than DRAIN_MAX")
        self.assertEqual(run.plant.rejected.get("MAC"), P.DRAIN_LATE + P.DRAIN_MAX)
        self.assertIsNone(run.plant.newest)

    def test_nothing_measured_is_nan_never_zero(self):
        h = P._Histogram()
        self.assertTrue(math.isnan(h.percentile(0.5)) and math.isnan(h.max))
        h.add(2e-3)
        self.assertAlmostEqual(h.percentile(0.5), 2e-3, delta=2e-3 * 0.011)
        self.assertEqual(h.max, 2e-3)


class CheaperContract(unittest.TestCase):
    """The per-message work made cheaper (one encoding a message sent, none a
    message taken) gives the same bytes and the same verdicts as before."""

    def test_fnv1a_four_bytes_a_turn_is_fnv1a(self):
        def one_a_turn(data, h=lagrange.contract.FNV_OFFSET_BASIS):
            for b in data:
                h = ((h ^ b) * lagrange.contract.FNV_PRIME) & ((1 << 64) - 1)
            return h
        for n in range(0, 41):
            data = os.urandom(n)
            self.assertEqual(lagrange.contract.fnv1a(data), one_a_turn(data), "%d bytes" % n)

    def test_a_sealed_encoding_is_the_sealed_messages_encoding(self):
        for publisher in ("plant", "actuatoré", ""):  # the checksum's offset follows the publisher's length
            for msg in (status("logger", 5), actuator_state(3, [1.0, 2.5])):
                msg.header.publisher = publisher
                fast = lagrange.contract.sealed_encoding(msg)
                checksum = msg.header.checksum
                self.assertEqual(fast, lagrange.contract.seal(msg).encode())
                self.assertEqual(checksum, msg.header.checksum)

    def test_intact_on_the_bytes_decoded_agrees_with_encoding_again(self):
        msg = actuator_state(3, [1.0, 2.5])
        data = msg.encode()
        self.assertTrue(lagrange.contract.intact(msg, data))
        msg.header.checksum ^= 2
        self.assertFalse(lagrange.contract.intact(msg, data), "the bytes carry another checksum than the message")
        damaged = bytearray(data)
        damaged[-5] ^= 1  # a torque changed after sealing: its checksum no longer matches
        d = lagrange.actuator_state_t.decode(bytes(damaged))
        self.assertFalse(lagrange.contract.intact(d, bytes(damaged)))
        self.assertFalse(lagrange.contract.intact(d))


class LockstepWatchdog(unittest.TestCase):
    """Item 8: in lockstep waiting is the protocol: the watchdog is off there
    (lockstep.stall_timeout ends a stalled run), so a late answer never brakes."""

    def test_an_answer_late_by_many_watchdog_periods_does_not_brake(self):
        brakes = []
        # Tick 5's answer comes with its re-sent position, 20 ms (20 periods) late;
        # the watchdog is 2 periods.
        run = FakeRun("lockstep", lambda t, u, dt: ([0.0, 0.0], [0.0, 0.0]), watchdog_periods=2,
                      brake=lambda: brakes.append(1), late=[5], duration=0.01, retransmit=0.02)
        self.addCleanup(run.close)
        self.assertEqual(run.plant.serve(), 0)
        run.handle_all()
        self.assertGreaterEqual(run.copies[5], 2, "tick 5 was answered late (re-sent)")
        self.assertEqual(brakes, [], "no brake in lockstep")
        self.assertEqual(run.plant.choice.watchdog_trips, 0)
        self.assertEqual(run.statuses[-1][0], "finished")
        truth6 = [t for t in run.truth if t.header.tick == 6][0]
        self.assertEqual((truth6.torque_source, list(truth6.tau_applied)), (P.TORQUE_COMMANDED, torque_of(5)))


if __name__ == "__main__":
    unittest.main()
