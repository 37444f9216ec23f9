"""The Python package's own tests (python/lagrange): standard library only.

    PYTHONPATH=python python3 -m unittest discover -s python/tests

The runs through it (a Python controller against the Java one, a run's log
against the C++ reader) are in tests/integration/external_controller_test.cpp.
"""

import json
import os
import struct
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "python"))

import lagrange  # noqa: E402
import lagrange.contract  # noqa: E402
import lagrange.external  # noqa: E402
import lagrange.external_plant  # noqa: E402
import lagrange.lcm  # noqa: E402
import lagrange.log  # noqa: E402
import lagrange.log_bounds  # noqa: E402
import lagrange.logfile  # noqa: E402


def event(channel, data, eventnum=0, timestamp=0):
    c = channel.encode()
    return struct.pack(">Iqqii", lagrange.logfile.SYNC_WORD, eventnum, timestamp, len(c), len(data)) + c + data


def position(tick, q, run_id=7):
    p = lagrange.plant_position_t()
    p.header = lagrange.header_t()
    p.header.tick, p.header.sim_time, p.header.run_id, p.header.publisher = tick, tick * 1e-3, run_id, "plant"
    p.num_joints, p.q = len(q), list(q)
    return lagrange.contract.seal(p)


class TypesAreCurrent(unittest.TestCase):
    def test_the_checked_in_classes_are_what_lcm_gen_writes(self):
        with tempfile.TemporaryDirectory() as out:
            subprocess.run([os.path.join(ROOT, "scripts", "generate-python-types.sh"), out], check=True)
            made = sorted(f for f in os.listdir(out) if f.endswith("_t.py"))
            kept = sorted(f for f in os.listdir(os.path.join(ROOT, "python", "lagrange")) if f.endswith("_t.py"))
            self.assertEqual(made, kept, "run scripts/generate-python-types.sh after changing lcmtypes/")
            self.assertEqual(len(made), len([f for f in os.listdir(os.path.join(ROOT, "lcmtypes")) if f.endswith(".lcm")]))
            for name in made:
                with open(os.path.join(out, name)) as a, open(os.path.join(ROOT, "python", "lagrange", name)) as b:
                    self.assertEqual(a.read(), b.read(), name + " is stale: run scripts/generate-python-types.sh")
            for name in made:  # and the package exports each
                self.assertTrue(hasattr(lagrange, name[:-3]), name)

    def test_a_count_larger_than_the_message_is_refused_at_once(self):
        c = lagrange.control_command_t()
        c.header = lagrange.header_t()
        c.num_joints, c.chain_order = 0, 0
        c.u = c.q_desired = c.q_error = c.theta = c.filter_state = []
        c.xi_error = []
        data = bytearray(c.encode())
        # chain_order is the int32 before the (empty) xi_error: rows of zero width, 2^31 - 1 of them
        data[-4:] = struct.pack(">i", 0x7FFFFFFF)
        import time
        start = time.monotonic()
        with self.assertRaisesRegex(ValueError, "chain_order larger than the message"):
            lagrange.control_command_t.decode(bytes(data))
        self.assertLess(time.monotonic() - start, 1.0)
        self.assertIsNone(lagrange.log.decode("CONTROL_COMMAND", bytes(data)))

    def test_a_boolean_array_decodes_to_a_list_that_encodes_again(self):
        a = lagrange.actuator_state_t()
        a.header = lagrange.header_t()
        a.num_joints, a.order, a.torque_steps = 2, 0, 1
        a.u_commanded, a.tau_applied, a.saturated, a.xi = [1.0, 2.0], [[1.0, 2.0]], [True, False], []
        data = a.encode()
        b = lagrange.actuator_state_t.decode(data)
        self.assertEqual(b.saturated, [True, False])
        self.assertEqual(b.encode(), data)


class Contract(unittest.TestCase):
    def test_the_checksum_uses_lagranges_basis_and_is_never_zero(self):
        self.assertEqual(lagrange.contract.fnv1a(b""), 1469598103934665603)
        # FNV-1a of "a" with lagrange's basis, by hand: (basis ^ 0x61) * prime mod 2^64
        self.assertEqual(lagrange.contract.fnv1a(b"a"), ((1469598103934665603 ^ 0x61) * 1099511628211) % 2**64)
        p = position(3, [0.1, 0.2])
        self.assertTrue(lagrange.contract.intact(p))
        self.assertEqual(p.header.checksum & 1, 1)
        p.q[1] = 0.25
        self.assertFalse(lagrange.contract.intact(p), "a changed angle breaks the checksum")

    def test_a_signed_datagram_authenticates_and_an_altered_one_does_not(self):
        key = lagrange.contract.Key(bytes(range(32)))
        datagram = key.sign(b"message")
        self.assertEqual(len(datagram), len(b"message") + 32)
        self.assertEqual(key.authenticate(datagram), b"message")
        self.assertIsNone(key.authenticate(datagram[:-1] + bytes([datagram[-1] ^ 1])))
        self.assertIsNone(key.authenticate(b"x" + datagram[1:]))
        self.assertIsNone(lagrange.contract.Key(bytes(32)).authenticate(datagram), "another key")
        self.assertIsNone(key.authenticate(b"short"))

    def test_a_key_file_must_hold_64_hex_digits(self):
        with tempfile.TemporaryDirectory() as d:
            good, bad = os.path.join(d, "good"), os.path.join(d, "bad")
            with open(good, "w") as f:
                f.write("ab" * 32 + "\n")
            with open(bad, "w") as f:
                f.write("not a key\n")
            self.assertEqual(lagrange.contract.Key.from_file(good).sign(b""), lagrange.contract.Key(b"\xab" * 32).sign(b""))
            with self.assertRaisesRegex(ValueError, "does not hold 64 hex digits"):
                lagrange.contract.Key.from_file(bad)
            with self.assertRaisesRegex(ValueError, "cannot read the run's key file"):
                lagrange.contract.Key.from_file(os.path.join(d, "missing"))

    def test_publish_utime_is_the_runs_clock(self):
        self.assertEqual(lagrange.contract.clock_offset_us({"LAGRANGE_CLOCK_OFFSET_US": "123"}), 123)
        import time
        from unittest import mock
        with mock.patch.dict(os.environ, {"LAGRANGE_CLOCK_OFFSET_US": "5000000"}):
            h = lagrange.contract.Headers(1, "controller")
        before = time.monotonic_ns() // 1000
        stamp = h.utime()
        after = time.monotonic_ns() // 1000
        self.assertTrue(before + 5000000 <= stamp <= after + 5000000, "monotonic time plus the launcher's offset")
        measured = lagrange.contract.clock_offset_us({})
        import time
        self.assertLess(abs(measured - (time.time_ns() - time.monotonic_ns()) // 1000), 100000)

    def test_publish_utime_never_goes_backwards(self):
        h = lagrange.contract.Headers(1, "controller")
        stamps = [h.utime() for _ in range(1000)]
        self.assertEqual(stamps, sorted(stamps))


class LogFile(unittest.TestCase):
    def write(self, data):
        f = tempfile.NamedTemporaryFile(suffix=".lcm", delete=False)
        f.write(data)
        f.close()
        self.addCleanup(os.unlink, f.name)
        return f.name

    def test_whole_events_are_read_in_order(self):
        path = self.write(event("A", b"1", 0) + event("B", b"22", 1) + event("A", b"", 2))
        with lagrange.logfile.LogReader(path) as r:
            got = [(e.channel, e.data, e.offset) for e in r]
            self.assertEqual(r.scan.events, 3)
            self.assertEqual(r.scan.channels, {"A": 2, "B": 1})
            self.assertEqual(r.scan.problems(), [])
        self.assertEqual(got, [("A", b"1", 0), ("B", b"22", 30), ("A", b"", 61)])

    def test_a_huge_length_is_named_with_its_offset_and_nothing_is_allocated(self):
        good = event("A", b"1")
        huge = struct.pack(">Iqqii", lagrange.logfile.SYNC_WORD, 1, 0, 1, 0x7FFFFFFF) + b"A"
        path = self.write(good + huge)
        with self.assertRaisesRegex(lagrange.logfile.LogError,
                                    "the event at byte 30 gives a data length of 2147483647 bytes; expected 0 to"):
            with lagrange.logfile.LogReader(path) as r:
                list(r)
        negative = struct.pack(">Iqqii", lagrange.logfile.SYNC_WORD, 1, 0, -5, 0)
        with self.assertRaisesRegex(lagrange.logfile.LogError, "channel name length of -5 bytes; expected 1 to 999"):
            with lagrange.logfile.LogReader(self.write(good + negative)) as r:
                list(r)

    def test_a_corrupt_stretch_is_skipped_and_counted(self):
        path = self.write(event("A", b"1") + b"garbage!" + event("B", b"2"))
        with lagrange.logfile.LogReader(path) as r:
            self.assertEqual([e.channel for e in r], ["A", "B"])
            self.assertEqual((r.scan.skipped_bytes, r.scan.first_skipped_at), (8, 30))
            self.assertIn("8 corrupt bytes between events were skipped", r.scan.problems()[0])

    def test_a_log_cut_short_reads_to_its_last_whole_event(self):
        whole = event("A", b"1") + event("B", b"22")
        path = self.write(whole + event("C", b"333")[:-2])
        with lagrange.logfile.LogReader(path) as r:
            self.assertEqual([e.channel for e in r], ["A", "B"])
            self.assertEqual(r.scan.unreadable_tail_bytes, len(event("C", b"333")) - 2)

    def test_a_file_that_is_no_log_is_named(self):
        with self.assertRaisesRegex(lagrange.logfile.LogError, "is not an LCM log: no event in its 11 bytes"):
            with lagrange.logfile.LogReader(self.write(b"hello world")) as r:
                list(r)
        with self.assertRaisesRegex(lagrange.logfile.LogError, "is a directory; expected an LCM log file"):
            lagrange.logfile.LogReader(tempfile.gettempdir())

    def test_a_fifo_or_a_device_is_refused_by_what_it_is_before_a_byte_is_read(self):
        with tempfile.TemporaryDirectory() as d:
            fifo = os.path.join(d, "fifo.lcm")
            os.mkfifo(fifo)
            link = os.path.join(d, "zero.lcm")
            os.symlink("/dev/zero", link)
            for path, kind in ((fifo, "a FIFO (named pipe)"), ("/dev/urandom", "a character device"),
                               (link, "a character device")):
                with self.assertRaises(lagrange.logfile.LogError) as caught:
                    lagrange.logfile.LogReader(path)
                self.assertEqual(str(caught.exception),
                                 "'%s' is %s; expected an LCM log file (a regular file)" % (path, kind))


GOLDEN = os.path.join(ROOT, "tests", "data", "golden")


def with_longest_publisher(message):
    message.header = lagrange.header_t()
    message.header.publisher = "p" * lagrange.log_bounds.MAX_PUBLISHER_BYTES
    return message


def actuator_state(tick, joints, steps):
    """An ACTUATOR_STATE whose lengths are all consistent: `steps` rows of `joints` joints."""
    m = lagrange.actuator_state_t()
    m.header = lagrange.header_t()
    m.header.tick, m.header.publisher = tick, "actuator"
    m.num_joints, m.order, m.u_commanded = joints, 0, [0.0] * joints
    m.torque_steps, m.tau_applied = steps, [[0.0] * joints for _ in range(steps)]
    m.saturated, m.xi = [False] * joints, []
    return m.encode()


class LogBounds(unittest.TestCase):
    def test_the_bounds_are_the_encoded_sizes_of_the_largest_messages(self):
        for n, m, steps in ((1, 0, 1), (2, 2, 3), (7, 4, 5)):
            sizes = lagrange.log_bounds.encoded_sizes(lagrange.log_bounds.Shape(n, m, steps))
            position = with_longest_publisher(lagrange.plant_position_t())
            position.num_joints, position.q = n, [0.0] * n
            truth = with_longest_publisher(lagrange.plant_truth_t())
            truth.num_joints, truth.q, truth.qdot, truth.tau_applied = n, [0.0] * n, [0.0] * n, [0.0] * n
            motor = with_longest_publisher(lagrange.plant_motor_t())
            motor.num_joints, motor.q, motor.num_rates, motor.qdot = n, [0.0] * n, n, [0.0] * n
            command = with_longest_publisher(lagrange.control_command_t())
            command.num_joints = n
            command.u = command.q_desired = command.q_error = command.theta = command.filter_state = [0.0] * n
            command.chain_order, command.xi_error = 4, [[0.0] * n for _ in range(4)]
            state = with_longest_publisher(lagrange.actuator_state_t())
            state.num_joints, state.order, state.u_commanded = n, m, [0.0] * n
            state.torque_steps, state.tau_applied = steps, [[0.0] * n for _ in range(steps)]
            state.saturated, state.xi = [False] * n, [[0.0] * n for _ in range(m)]
            for channel, message in (("PLANT_POSITION", position), ("PLANT_TRUTH", truth), ("PLANT_MOTOR", motor),
                                     ("CONTROL_COMMAND", command), ("ACTUATOR_STATE", state)):
                self.assertEqual(sizes[channel], len(message.encode()), (channel, n, m, steps))

    def test_every_golden_log_loads_whole_within_its_scenarios_bounds(self):
        shapes = {"rigid_2dof_lockstep": "2 joints, actuator order 0, 1 torque step a tick",
                  "chain_m2_lockstep": "2 joints, actuator order 2, 1 torque step a tick",
                  "panda_theorem1_lockstep": "7 joints, actuator order 0, 1 torque step a tick"}
        for name, shape in shapes.items():
            path = os.path.join(GOLDEN, name + ".lcm")
            self.assertEqual(lagrange.log.bounds_of_log(path).origin, "the log's scenario (%s)" % shape)
        for name in sorted(os.listdir(GOLDEN)):
            with lagrange.logfile.LogReader(os.path.join(GOLDEN, name),
                                            lagrange.log.bounds_of_log(os.path.join(GOLDEN, name))) as r:
                list(r)
                self.assertEqual(r.scan.oversized_events, 0, name)

    # The attack, smaller: 200 000 one-joint rows (1.6 MB; 30 million
    # took load to 3.3 GB) in a log of a 2-joint scenario with 1 torque step a tick.
    def test_an_event_larger_than_its_scenario_allows_is_skipped_unread_and_named(self):
        with lagrange.logfile.LogReader(os.path.join(GOLDEN, "rigid_2dof_lockstep.lcm")) as r:
            scenario = next(iter(r)).data
        head = event("SCENARIO", scenario, 0) + event("ACTUATOR_STATE", actuator_state(0, 2, 1), 1)
        crafted = event("ACTUATOR_STATE", actuator_state(7, 1, 200000), 2)
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "run.lcm"), "wb") as f:
                f.write(head + crafted + event("ACTUATOR_STATE", actuator_state(1, 2, 1), 3))
            run = lagrange.log.load(d, numpy=False)
        self.assertEqual(run.channels["ACTUATOR_STATE"]["header.tick"], [0, 1])
        self.assertEqual(run.scan.oversized_events, 1)
        problems = "\n".join(run.scan.problems())
        bound = lagrange.log_bounds.encoded_sizes(lagrange.log_bounds.Shape(2, 0, 1))["ACTUATOR_STATE"] + 32
        self.assertIn("1 event was larger than its channel's messages can be and skipped unread, never decoded "
                      "(ACTUATOR_STATE at byte %d (tick 7): %d bytes, at most %d expected); the bound is the "
                      "message with the counts of the log's scenario (2 joints, actuator order 0, 1 torque step "
                      "a tick)" % (len(head), len(crafted) - 42, bound), problems)

    def test_a_scenario_larger_than_any_scenario_refuses_the_log(self):
        size = lagrange.log_bounds.MAX_SCENARIO_EVENT_BYTES + 1
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "run.lcm"), "wb") as f:
                f.write(event("SCENARIO", bytes(size)))
            with self.assertRaisesRegex(lagrange.logfile.LogError,
                                        "the SCENARIO at byte 0 holds %d bytes; a scenario is at most %d"
                                        % (size, size - 1)):
                lagrange.log.load(d)


class Lcm(unittest.TestCase):
    def test_publish_and_subscribe_through_liblcm(self):
        got = []
        with lagrange.lcm.LCM("memq://") as lc:
            sub = lc.subscribe("CH.*", lambda channel, data: got.append((channel, data)))
            lc.publish("CH1", b"\x00one")
            lc.publish("OTHER", b"two")
            lc.publish("CH2", b"x" * 100000)
            while lc.handle_timeout(10) > 0:
                pass
            self.assertGreaterEqual(lc.fileno(), 0)
            lc.unsubscribe(sub)
            lc.publish("CH1", b"after")
            lc.handle_timeout(10)
        self.assertEqual(got, [("CH1", b"\x00one"), ("CH2", b"x" * 100000)])

    def test_an_exception_in_a_handler_is_raised_from_handle(self):
        def fail(channel, data):
            raise KeyError("from the handler")

        with lagrange.lcm.LCM("memq://") as lc:
            lc.subscribe("CH", fail)
            lc.publish("CH", b"1")
            with self.assertRaises(KeyError):
                lc.handle_timeout(100)

    def test_a_bad_url_is_named(self):
        with self.assertRaisesRegex(lagrange.lcm.LCMError, "could not be created on 'nonsense://x'"):
            lagrange.lcm.LCM("nonsense://x")

    def test_without_liblcm_the_error_names_the_package(self):
        env = dict(os.environ, LAGRANGE_LIBLCM="/nonexistent/liblcm.so.1", PYTHONPATH=os.path.join(ROOT, "python"))
        r = subprocess.run([sys.executable, "-c", "import lagrange.lcm; lagrange.lcm.LCM('memq://')"], env=env,
                           capture_output=True, text=True)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("install the Debian package liblcm1", r.stderr)

    def test_a_log_written_by_liblcm_loads_into_columns(self):
        with tempfile.TemporaryDirectory() as d:
            with lagrange.lcm.LCM("file://%s/run.lcm?mode=w" % d) as lc:
                for tick in range(5):
                    lc.publish("PLANT_POSITION", position(tick, [tick * 0.5, -tick]).encode())
                lc.publish("PLANT_POSITION", position(2, [1.0, -2.0]).encode())  # a lockstep re-send
                damaged = position(5, [9.0, 9.0])
                damaged.q[0] = 8.0  # recorded as it arrived, checksum broken
                lc.publish("PLANT_POSITION", damaged.encode())
                lc.publish("PLANT_TRUTH", b"not a message")
                lc.publish("SOMETHING_ELSE", b"x")
            run = lagrange.log.load(d, numpy=False)
        pos = run.channels["PLANT_POSITION"]
        self.assertEqual(pos["header.tick"], [0, 1, 2, 3, 4])
        self.assertEqual(pos["t"], [0.0, 1e-3, 2e-3, 3e-3, 4e-3])
        self.assertEqual(pos["q"][3], [1.5, -3.0])
        self.assertEqual(run.repeated, {"PLANT_POSITION": 1})
        self.assertEqual(run.corrupt, {"PLANT_POSITION": 1})
        self.assertEqual(run.undecodable, {"PLANT_TRUTH": 1})
        self.assertEqual(run.unknown_channels, {"SOMETHING_ELSE": 1})
        self.assertIsNone(run.summary)

    def test_the_log_itself_loads_as_its_folder_does_with_the_scenario_as_a_dict(self):
        with tempfile.TemporaryDirectory() as d:
            with lagrange.lcm.LCM("file://%s/run.lcm?mode=w" % d) as lc:
                for tick in range(3):
                    lc.publish("PLANT_POSITION", position(tick, [tick * 0.5, -tick]).encode())
            with open(os.path.join(d, "config.resolved.json"), "w") as f:
                json.dump({"name": "two", "controller": {"kp": [100.0, 8.0]}}, f)
            by_folder = lagrange.log.load(d, numpy=False)
            by_log = lagrange.log.load(os.path.join(d, "run.lcm"), numpy=False)
        self.assertEqual(by_log.channels, by_folder.channels)
        self.assertEqual(by_log.dir, os.path.abspath(d))
        self.assertEqual(by_log.scenario["controller"]["kp"], [100.0, 8.0])
        self.assertEqual(by_folder.scenario, by_log.scenario)

    def test_a_directory_without_a_log_is_named(self):
        with tempfile.TemporaryDirectory() as d:
            with self.assertRaisesRegex(lagrange.logfile.LogError, "has no run.lcm; expected the output directory"):
                lagrange.log.load(d)


class ExternalController(unittest.TestCase):
    """The contract around step(t, q), on LCM's in-process memq:// bus: this
    test plays the plant and reads the commands."""

    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.addCleanup(self.dir.cleanup)
        key_file = os.path.join(self.dir.name, "run.key")
        with open(key_file, "w") as f:
            f.write("5a" * 32 + "\n")
        self.key = lagrange.contract.Key(b"\x5a" * 32)
        self.calls = []
        env = {"LAGRANGE_LCM_URL": "memq://", "LAGRANGE_RUN_ID": "7", "LAGRANGE_KEY_FILE": key_file,
               "LAGRANGE_JOINTS": "2", "LAGRANGE_MODE": "lockstep"}
        self.controller = lagrange.external.Controller(self.step, environ=env)
        self.commands = []
        self.controller.lcm.subscribe("CONTROL_COMMAND", self.on_command)

    def step(self, t, q):
        self.calls.append((t, list(q)))
        return [-q[0], -2.0 * q[1]]

    def on_command(self, _channel, data):
        payload = self.key.authenticate(data)
        self.assertIsNotNone(payload, "every datagram carries the run's MAC")
        c = lagrange.control_command_t.decode(payload)
        self.assertTrue(lagrange.contract.intact(c))
        self.commands.append(c)

    def send(self, message, key=None):
        self.controller.lcm.publish("PLANT_POSITION", (key or self.key).sign(message.encode()))
        while self.controller.lcm.handle_timeout(5) > 0:
            pass

    def test_answers_a_position_once_and_a_resent_one_with_the_same_command(self):
        self.send(position(0, [1.0, 2.0]))
        self.send(position(1, [0.5, 0.25]))
        self.send(position(1, [0.5, 0.25]))  # lockstep re-sends tick 1
        self.assertEqual(len(self.calls), 2, "the law is never stepped twice on one sample")
        self.assertEqual([c.header.tick for c in self.commands], [0, 1, 1])
        self.assertEqual([list(c.u) for c in self.commands], [[-1.0, -4.0], [-0.5, -0.5], [-0.5, -0.5]])
        self.assertEqual([c.header.seq for c in self.commands], [1, 2, 3], "a re-sent command has a new seq")
        c = self.commands[1]
        self.assertEqual((c.header.run_id, c.header.publisher, c.input_position_tick, c.input_actuator_tick),
                         (7, "controller", 1, -1))
        self.assertEqual(c.header.sim_time, 1e-3)

    def test_drops_what_is_not_this_runs_plant(self):
        self.send(position(0, [1.0, 2.0]), key=lagrange.contract.Key(bytes(32)))  # forged: another key
        self.send(position(0, [1.0, 2.0], run_id=8))  # another run
        other = position(0, [1.0, 2.0])
        other.header.publisher = "actuator"
        self.send(lagrange.contract.seal(other))
        damaged = position(0, [1.0, 2.0])
        damaged.q[0] = 3.0  # checksum no longer matches
        self.send(damaged)
        self.send(position(0, [1.0, 2.0, 3.0]))  # three joints for a two-joint arm
        self.assertEqual((self.calls, self.commands, self.controller.rejected), ([], [], 5))
        self.send(position(5, [1.0, 2.0]))
        self.send(position(4, [1.0, 2.0]))  # older than one answered: never step back
        self.assertEqual([c.header.tick for c in self.commands], [5])

    def test_a_law_that_returns_the_wrong_size_is_named(self):
        self.controller.step = lambda t, q: [1.0]
        with self.assertRaisesRegex(lagrange.external.ContractError,
                                    "step\\(\\) returned 1 numbers for u; expected 2 \\(one per joint\\)"):
            self.send(position(0, [1.0, 2.0]))

    def test_a_law_that_returns_a_non_finite_value_is_named_with_its_sample(self):
        self.send(position(0, [1.0, 2.0]))
        self.controller.step = lambda t, q: [0.0, float("nan")]
        with self.assertRaisesRegex(lagrange.external.ContractError,
                                    "step\\(\\) returned nan for u\\[1\\] \\(joint 2\\) at the sample of tick 3 "
                                    "\\(t = 0.003 s\\); expected finite numbers"):
            self.send(position(3, [1.0, 2.0]))
        self.assertEqual([c.header.tick for c in self.commands], [0], "nothing published for the bad sample")

    def test_ends_with_finished_when_the_plant_finishes(self):
        states = []
        publish_status = self.controller.publish_status
        self.controller.publish_status = lambda state: (states.append(state), publish_status(state))
        s = lagrange.status_t()
        s.header = lagrange.header_t()
        s.header.run_id, s.header.publisher = 7, "plant"
        s.process, s.state, s.message, s.num_channels, s.channels = "plant", "finished", "", 0, []
        s.loop = lagrange.loop_stats_t()
        s.loop.scheduler = ""
        self.controller.lcm.publish("STATUS", self.key.sign(lagrange.contract.seal(s).encode()))
        self.assertEqual(self.controller.serve(), 0)
        self.assertTrue(self.controller.plant_finished)
        self.assertEqual(states, ["ready", "finished", "finished", "finished"])

    def test_the_runs_scenario_is_a_dict_or_a_named_error(self):
        self.assertIsNone(self.controller.scenario, "no LAGRANGE_CONFIG_JSON: no scenario")
        path = os.path.join(self.dir.name, "config.resolved.json")
        with open(path, "w") as f:
            f.write('{"reference": {"offset": [0.5, -0.2]}, "controller": {"type": "external"}}')
        s = lagrange.external.scenario({"LAGRANGE_CONFIG_JSON": path})
        self.assertEqual(s["reference"]["offset"], [0.5, -0.2])
        with self.assertRaisesRegex(lagrange.external.ContractError, "LAGRANGE_CONFIG_JSON is not set"):
            lagrange.external.scenario({})
        with self.assertRaisesRegex(lagrange.external.ContractError,
                                    "cannot read the run's scenario from LAGRANGE_CONFIG_JSON=.*missing.json"):
            lagrange.external.scenario({"LAGRANGE_CONFIG_JSON": path + ".missing.json"})


class PlantGuards(unittest.TestCase):
    """lagrange.external_plant's realtime torque rule and a bridge's guards (docs/hardware.md)."""

    def test_the_newest_torque_is_applied_then_held_then_zeroed_as_the_built_in_plant_does(self):
        c = lagrange.external_plant.TorqueChoice(max_age=2, hold_periods=3, hold=True)
        tau = [1.0, -2.0]
        P = lagrange.external_plant
        self.assertEqual(c.choose(0, None, None, 2), ([0.0, 0.0], P.TORQUE_ZERO, -1, False))
        self.assertEqual(c.zeroed, 0, "nothing can have answered before the first sample")
        self.assertEqual(c.choose(12, 10, tau, 2)[1:3], (P.TORQUE_COMMANDED, 10))
        self.assertEqual(c.choose(13, 10, tau, 2)[:3], (tau, P.TORQUE_HELD, 10))
        self.assertEqual(c.choose(15, 10, tau, 2)[1], P.TORQUE_HELD)
        self.assertEqual(c.choose(16, 10, tau, 2)[:3], ([0.0, 0.0], P.TORQUE_ZERO, -1))
        self.assertEqual((c.held, c.zeroed, c.watchdog_trips), (2, 1, 0))
        zero = lagrange.external_plant.TorqueChoice(max_age=2, hold_periods=3, hold=False)
        self.assertEqual(zero.choose(13, 10, tau, 2)[1], P.TORQUE_ZERO)

    def test_the_watchdog_zeroes_an_old_torque_whatever_the_policy_and_trips_once_per_silence(self):
        P = lagrange.external_plant
        c = P.TorqueChoice(max_age=2, hold_periods=20, hold=True, watchdog_periods=5)
        self.assertEqual(c.choose(15, 10, [1.0], 1)[1], P.TORQUE_HELD)  # age 5: still the policy's
        self.assertEqual(c.choose(16, 10, [1.0], 1), ([0.0], P.TORQUE_ZERO, -1, True))  # age 6: tripped
        self.assertEqual(c.choose(17, 10, [1.0], 1), ([0.0], P.TORQUE_ZERO, -1, False))  # said once
        self.assertEqual(c.choose(18, 17, [2.0], 1)[:3], ([2.0], P.TORQUE_COMMANDED, 17))  # answers again
        self.assertEqual(c.choose(30, 17, [2.0], 1)[3], True)  # a second silence trips again
        self.assertEqual(c.watchdog_trips, 2)

    def test_limits_clip_the_torque_and_name_a_crossed_position_or_rate(self):
        limits = lagrange.external_plant.Limits(torque=[10.0, 2.0], position=[(-1.0, 1.0), (0.0, 3.0)],
                                                rate=[5.0, 5.0])
        self.assertEqual(limits.clip([12.0, -1.0]), ([10.0, -1.0], True))
        self.assertEqual(limits.clip([-3.0, 1.5]), ([-3.0, 1.5], False))
        self.assertIsNone(limits.breach([0.5, 1.0], [4.9, -4.9]))
        self.assertEqual(limits.breach([0.5, -0.25], [0.0, 0.0]),
                         "joint 2's position -0.25 rad is outside its limits [0, 3]")
        self.assertEqual(limits.breach([0.5, 1.0], [0.0, -6.0]), "joint 2's rate -6 rad/s is beyond its limit 5")
        self.assertEqual(limits.breach([float("nan"), 1.0], [0.0, 0.0]),
                         "joint 1's position nan rad is outside its limits [-1, 1]")
        with self.assertRaisesRegex(lagrange.external.ContractError, "every torque limit must be > 0"):
            lagrange.external_plant.Limits(torque=[1.0, 0.0])
        with self.assertRaisesRegex(lagrange.external.ContractError, "lower < upper"):
            lagrange.external_plant.Limits(position=[(1.0, -1.0)])
        with self.assertRaisesRegex(lagrange.external.ContractError, r"one \(lower, upper\) pair per joint"):
            lagrange.external_plant.Limits(position=[-1.0, 1.0])
        with self.assertRaisesRegex(lagrange.external.ContractError, "3 torque limits for 2 joints"):
            lagrange.external_plant.Limits(torque=[1.0, 1.0, 1.0]).check_sizes(2)


if __name__ == "__main__":
    unittest.main()
