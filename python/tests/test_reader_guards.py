"""lagrange.log.load against crafted run folders (issue #53): every file of a
run is looked at before it is read, as the C++ readers do, and the rows kept
are the run's own ticks. Each test makes its folder itself; what could hang
(a FIFO) runs in a child with a timeout, so a regression fails, never waits.

    PYTHONPATH=python python3 -S -m unittest discover -s python/tests
"""

import json
import os
import struct
import subprocess
import sys
import tempfile
import time
import tracemalloc
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PYTHON = os.path.join(ROOT, "python")
sys.path.insert(0, PYTHON)

import lagrange  # noqa: E402
import lagrange.contract  # noqa: E402
import lagrange.log  # noqa: E402
import lagrange.log_bounds  # noqa: E402
import lagrange.logfile  # noqa: E402
import lagrange.programs  # noqa: E402

GOLDEN = os.path.join(ROOT, "tests", "data", "golden")
LogError = lagrange.logfile.LogError


def event(channel, data, eventnum=0):
    c = channel.encode()
    return struct.pack(">Iqqii", lagrange.logfile.SYNC_WORD, eventnum, 0, len(c), len(data)) + c + data


def position(tick, q):
    """A PLANT_POSITION of `tick`, sealed (its checksum matches)."""
    p = lagrange.plant_position_t()
    p.header = lagrange.header_t()
    p.header.tick, p.header.sim_time, p.header.run_id, p.header.publisher = tick, tick * 1e-3, 7, "plant"
    p.num_joints, p.q = len(q), list(q)
    return lagrange.contract.seal(p).encode()


def status(tick):
    s = lagrange.status_t()
    s.header = lagrange.header_t()
    s.header.tick, s.header.run_id, s.header.publisher = tick, 7, "plant"
    s.process, s.state, s.last_tick, s.tracking_error, s.message = "plant", "running", tick, 0.0, ""
    s.num_channels, s.channels, s.loop = 0, [], lagrange.loop_stats_t()
    return lagrange.contract.seal(s).encode()


def golden_scenario():
    """The SCENARIO event's data of a 1 s run at 1 kHz: ticks 0 to 1000."""
    with lagrange.logfile.LogReader(os.path.join(GOLDEN, "rigid_2dof_lockstep.lcm"), only_channel="SCENARIO") as r:
        return next(iter(r)).data


def write_run(folder, ticks, scenario=True):
    """run.lcm in `folder`: the golden SCENARIO (when `scenario`), then a
    PLANT_POSITION for each of `ticks`, in that order; returns each row's
    byte offset."""
    offsets = []
    with open(os.path.join(folder, "run.lcm"), "wb") as f:
        if scenario:
            f.write(event("SCENARIO", golden_scenario()))
        for n, tick in enumerate(ticks):
            offsets.append(f.tell())
            f.write(event("PLANT_POSITION", position(tick, [tick * 1e-3, -1.0]), n + 1))
    return offsets


def _at_most_1_gib():
    import resource

    resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30))


def isolated(code, timeout=30):
    """Runs `code` in a child python3 -S with the package on its path, and
    returns its standard output; the test fails (not hangs) past `timeout`,
    and the child's memory is held to 1 GiB (a file read whole that has no
    end, /dev/zero, is a MemoryError there, not the machine's memory)."""
    env = dict(os.environ, PYTHONPATH=PYTHON)
    try:
        done = subprocess.run([sys.executable, "-S", "-c", code], env=env, capture_output=True, text=True,
                              timeout=timeout, preexec_fn=_at_most_1_gib)
    except subprocess.TimeoutExpired:
        raise AssertionError("still running after %d s (it waits on a FIFO?): %s" % (timeout, code)) from None
    if done.returncode != 0:
        raise AssertionError("the child failed (%d): %s" % (done.returncode, done.stderr))
    return done.stdout


# In the child: load(folder) and print how it ended, as JSON, with the time it took.
_LOAD_AND_SAY = """
import json, sys, time
import lagrange.log
start = time.monotonic()
try:
    lagrange.log.load(sys.argv[1] if len(sys.argv) > 1 else %r, numpy=False)
    said = {"error": None}
except Exception as e:
    said = {"error": type(e).__name__, "message": str(e)}
said["seconds"] = time.monotonic() - start
print(json.dumps(said))
"""


class RunFiles(unittest.TestCase):
    """summary.json, config.resolved.yaml, config.resolved.json and run.lcm
    are each refused, by what they are, unless a regular file of bounded size."""

    def folder(self):
        d = tempfile.TemporaryDirectory()
        self.addCleanup(d.cleanup)
        write_run(d.name, range(3))
        return d.name

    def refusal(self, folder):
        with self.assertRaises(LogError) as caught:
            lagrange.log.load(folder, numpy=False)
        return str(caught.exception)

    def test_a_fifo_in_place_of_any_file_of_a_run_is_refused_at_once(self):
        expected = {"summary.json": "the run's summary.json",
                    "config.resolved.yaml": "the run's resolved scenario",
                    "config.resolved.json": "the run's resolved scenario as JSON",
                    "run.lcm": "an LCM log file"}
        for name, what in expected.items():
            d = self.folder()
            path = os.path.join(d, name)
            if os.path.exists(path):
                os.unlink(path)
            os.mkfifo(path)  # no writer: opening it to read would wait for ever
            said = json.loads(isolated(_LOAD_AND_SAY % d))
            self.assertEqual(said["error"], "LogError", (name, said))
            self.assertEqual(said["message"], "'%s' is a FIFO (named pipe); expected %s (a regular file)"
                             % (path, what))
            self.assertLess(said["seconds"], 10, name)

    def test_a_fifo_given_as_the_log_itself_is_refused(self):
        d = self.folder()
        fifo = os.path.join(d, "other.lcm")
        os.mkfifo(fifo)
        said = json.loads(isolated(_LOAD_AND_SAY % fifo))
        self.assertEqual((said["error"], said["message"]),
                         ("LogError", "'%s' is a FIFO (named pipe); expected an LCM log file (a regular file)" % fifo))

    def test_a_link_to_a_device_or_to_proc_is_refused_before_a_byte_is_read(self):
        for target, kind in (("/dev/zero", "a character device"),
                             ("/proc/self/status", "a file of /proc (made up by the kernel as it is read)")):
            for name, what in (("summary.json", "the run's summary.json"),
                               ("config.resolved.yaml", "the run's resolved scenario"),
                               ("config.resolved.json", "the run's resolved scenario as JSON")):
                d = self.folder()
                link = os.path.join(d, name)
                os.symlink(target, link)
                said = json.loads(isolated(_LOAD_AND_SAY % d))
                self.assertEqual((said["error"], said["message"]),
                                 ("LogError", "'%s' is %s; expected %s (a regular file)" % (link, kind, what)))

    def test_a_link_to_nothing_is_named(self):
        d = self.folder()
        link = os.path.join(d, "summary.json")
        os.symlink(os.path.join(d, "gone"), link)
        self.assertEqual(self.refusal(d), "cannot read '%s' (No such file or directory); expected the run's "
                                          "summary.json" % link)

    def test_a_summary_larger_than_16_mib_is_refused_unread(self):
        d = self.folder()
        summary = os.path.join(d, "summary.json")
        with open(summary, "wb") as f:
            f.truncate(300 << 20)  # 300 MiB, sparse: nothing written, and nothing may be read
        start = time.monotonic()
        self.assertEqual(self.refusal(d),
                         "'%s' is 300 MiB; expected the run's summary.json of at most 16 MiB" % summary)
        self.assertLess(time.monotonic() - start, 5)
        self.assertEqual(lagrange.log.MAX_SUMMARY_BYTES, 16 << 20)

    def test_a_resolved_scenario_larger_than_any_log_holds_is_refused_unread(self):
        for name, what in (("config.resolved.yaml", "the run's resolved scenario"),
                           ("config.resolved.json", "the run's resolved scenario as JSON")):
            d = self.folder()
            path = os.path.join(d, name)
            with open(path, "wb") as f:
                f.truncate(lagrange.log.MAX_RESOLVED_BYTES + 1)
            self.assertEqual(self.refusal(d), "'%s' is %s; expected %s of at most %s"
                             % (path, lagrange.logfile.size_text(lagrange.log.MAX_RESOLVED_BYTES + 1), what,
                                lagrange.logfile.size_text(lagrange.log.MAX_RESOLVED_BYTES)))

    def test_a_summary_nested_200000_deep_is_refused_without_recursion(self):
        d = self.folder()
        summary = os.path.join(d, "summary.json")
        with open(summary, "w") as f:
            f.write("[" * 200000 + "]" * 200000)
        self.assertEqual(self.refusal(d), "'%s' nests JSON deeper than 32 levels; expected "
                                          "the run's summary.json" % summary)
        with open(summary, "w") as f:  # objects count as lists do, after other text
            f.write('{"a": [1, 2], "b": ' + '{"c": ' * 40 + "1" + "}" * 41)
        self.assertIn("nests JSON deeper than 32 levels", self.refusal(d))

    def test_brackets_in_strings_do_not_nest_and_32_levels_read(self):
        d = self.folder()
        deepest = "[" * 31 + "]" * 31  # in the summary's object: 32 levels
        with open(os.path.join(d, "summary.json"), "w") as f:
            json.dump({"status": "completed", "note": "[{" * 1000 + '\\"[', "deep": json.loads(deepest)}, f)
        run = lagrange.log.load(d, numpy=False)
        self.assertEqual(run.summary["note"], "[{" * 1000 + '\\"[')
        self.assertEqual(run.summary["status"], "completed")

    def test_a_summary_that_is_not_json_or_not_utf8_is_named(self):
        d = self.folder()
        summary = os.path.join(d, "summary.json")
        with open(summary, "w") as f:
            f.write('{"status": ')
        message = self.refusal(d)
        self.assertTrue(message.startswith("'%s' is not JSON (Expecting value: line 1 column 12" % summary), message)
        self.assertTrue(message.endswith("; expected the run's summary.json"), message)
        with open(summary, "wb") as f:
            f.write(b'{"status": "\xff"}')
        self.assertEqual(self.refusal(d), "'%s' is not UTF-8 text (byte 12 is not); expected the run's "
                                          "summary.json" % summary)
        os.unlink(summary)
        resolved = os.path.join(d, "config.resolved.yaml")
        with open(resolved, "wb") as f:
            f.write(b"name: \xc3")
        self.assertEqual(self.refusal(d), "'%s' is not UTF-8 text (byte 6 is not); expected the run's resolved "
                                          "scenario" % resolved)

    def test_regular_files_within_their_bounds_read_as_before(self):
        d = self.folder()
        with open(os.path.join(d, "summary.json"), "w") as f:
            json.dump({"status": "completed", "verdict": {"tracking": "met"}}, f)
        with open(os.path.join(d, "config.resolved.yaml"), "w") as f:
            f.write("name: x\n")
        with open(os.path.join(d, "config.resolved.json"), "w") as f:
            json.dump({"name": "x"}, f)
        os.symlink(os.path.join(d, "summary.json"), os.path.join(d, "linked.json"))  # not a run file: unread
        run = lagrange.log.load(d, numpy=False)
        self.assertEqual((run.summary["status"], run.verdict, run.scenario_yaml, run.scenario),
                         ("completed", {"tracking": "met"}, "name: x\n", {"name": "x"}))


class RowsOfTheRun(unittest.TestCase):
    """Rows whose tick is not one of the log's scenario's, 0 to
    round(duration * publish_rate), are dropped unread and counted."""

    def test_rows_outside_the_scenarios_ticks_are_dropped_and_counted(self):
        ticks = [0, 1, 10 ** 15, 2, -1, 1000, 1001, 3]
        with tempfile.TemporaryDirectory() as d:
            offsets = write_run(d, ticks)
            with open(os.path.join(d, "run.lcm"), "ab") as f:
                f.write(event("STATUS", status(5)) + event("STATUS", status(10 ** 15)))
            run = lagrange.log.load(d, numpy=False)
        self.assertEqual(run.bounds.last_tick, 1000)
        self.assertEqual(run.channels["PLANT_POSITION"]["header.tick"], [0, 1, 2, 1000, 3])
        self.assertEqual(run.channels["PLANT_POSITION"]["q"][3], [1.0, -1.0])
        self.assertEqual([m.header.tick for m in run.messages["STATUS"]], [5])
        self.assertEqual(run.out_of_range, {"PLANT_POSITION": 3, "STATUS": 1})
        self.assertEqual(run.first_out_of_range, [("PLANT_POSITION", offsets[2], 10 ** 15),
                                                  ("PLANT_POSITION", offsets[4], -1),
                                                  ("PLANT_POSITION", offsets[6], 1001)])
        self.assertIn("4 messages claimed a tick outside the run's ticks 0 to 1000 (the log's scenario: duration 1 s "
                      "at plant.publish_rate 1000 Hz) and were left out, never decoded (PLANT_POSITION at byte %d "
                      "(tick 1000000000000000); PLANT_POSITION at byte %d (tick -1); PLANT_POSITION at byte %d "
                      "(tick 1001); ...)" % (offsets[2], offsets[4], offsets[6]), run.problems())
        self.assertEqual((run.corrupt, run.undecodable, run.repeated), ({}, {}, {}))

    def test_without_a_scenario_the_projects_limit_bounds_the_ticks(self):
        with tempfile.TemporaryDirectory() as d:
            write_run(d, [0, 5000, 10 ** 8, 10 ** 8 + 1, 10 ** 15], scenario=False)
            run = lagrange.log.load(d, numpy=False)
        self.assertEqual(run.channels["PLANT_POSITION"]["header.tick"], [0, 5000, 10 ** 8])
        self.assertEqual(run.out_of_range, {"PLANT_POSITION": 2})
        self.assertEqual(run.bounds.ticks_origin, "no SCENARIO in the log: the project's limit of 100000000 samples "
                                                  "a run")

    def test_the_last_tick_is_the_scenarios_as_cpp_rounds_it(self):
        scenario = golden_scenario().decode("latin-1")
        for duration, rate, last in (("1", "1000", 1000), ("2.5", "3", 8), ("0.0015", "1000", 2),
                                     (".inf", "1000", None), ("1e9", "1000", None)):
            yaml = scenario.replace("\nduration: 1\n", "\nduration: %s\n" % duration).replace(
                "  publish_rate: 1000\n", "  publish_rate: %s\n" % rate)
            self.assertEqual(lagrange.log_bounds.last_tick_of_scenario(yaml), last, (duration, rate))

    def test_every_golden_log_keeps_all_its_rows(self):
        for name in sorted(os.listdir(GOLDEN)):
            run = lagrange.log.load(os.path.join(GOLDEN, name), numpy=False, verify=False)
            self.assertEqual((run.out_of_range, run.problems()), ({}, []), name)
            self.assertEqual(run.bounds.last_tick, 1000, name)
            self.assertEqual(run.channels["PLANT_POSITION"]["header.tick"], list(range(1001)), name)

    # The attack, smaller: 3 million ticks (582 MB) for a 1 001-tick
    # scenario took load to a MemoryError at 3.8 GB. Here 40 000 rows past the
    # scenario's end and 20 000 copies of one of its ticks: what load holds at
    # its peak is the scenario's 1 001 rows, not the file's 60 000.
    def test_memory_grows_with_the_scenario_not_with_the_file(self):
        with tempfile.TemporaryDirectory() as d:
            scenario_rows = list(range(1001))
            write_run(d, scenario_rows)
            base = self.peak_of_load(d)
            row = position(0, [0.0, -1.0])
            with open(os.path.join(d, "run.lcm"), "ab") as f:
                for k in range(40000):  # ticks 1001 on: the bytes of a row, only the tick changed
                    f.write(event("PLANT_POSITION", row[:8] + struct.pack(">q", 1001 + k) + row[16:]))
                copy = event("PLANT_POSITION", position(500, [0.5, -1.0]))
                f.write(copy * 20000)
            peak = self.peak_of_load(d)
            run = lagrange.log.load(d, numpy=False)
        self.assertEqual(run.channels["PLANT_POSITION"]["header.tick"], scenario_rows)
        self.assertEqual(run.out_of_range, {"PLANT_POSITION": 40000})
        self.assertEqual(run.repeated, {"PLANT_POSITION": 20000})
        # 60 000 decoded rows would hold about 60 times the 1 001 rows' memory.
        self.assertLess(peak, 2 * base + (1 << 20), (peak, base))

    @staticmethod
    def peak_of_load(folder):
        tracemalloc.start()
        try:
            lagrange.log.load(folder, numpy=False)
            return tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()


class Programs(unittest.TestCase):
    """lagrange.run and lagrange.sweep refuse what their program would take
    for something else, before anything runs."""

    def scenario_file(self):
        f = tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False)
        f.write("name: x\n")
        f.close()
        self.addCleanup(os.unlink, f.name)
        return f.name

    def test_a_keyword_that_is_no_scenario_key_is_refused_naming_it(self):
        scenario = self.scenario_file()
        cases = {"controller__kp=1,x": "the part 'kp=1,x'", "controller__kp x": "the part 'kp x'",
                 "controller____kp": "an empty part", "controller__": "an empty part",
                 "contrôleur__kp": "the part 'contrôleur'"}
        for keyword, why in cases.items():
            with self.assertRaises(lagrange.LagrangeError) as caught:
                lagrange.run(scenario, out=os.path.join(tempfile.gettempdir(), "never-made"), **{keyword: 3})
            self.assertEqual(str(caught.exception),
                             "the keyword %r is not a scenario key: %s; expected a key's parts (letters, digits and "
                             "_) joined by __ for each ., e.g. controller__kp for controller.kp" % (keyword, why))
            self.assertIsNone(caught.exception.exit_code)
        self.assertFalse(os.path.exists(os.path.join(tempfile.gettempdir(), "never-made")))

    def test_keys_as_the_scenario_writes_them_pass_as_set_options(self):
        sets, keywords = lagrange.programs._sets({"controller__kp": [100, 8], "faults__channels__PLANT_POSITION":
                                                  {"drop": 0.1}, "duration": 2.0})
        self.assertEqual(sets, ["--set", "controller.kp=[100, 8]", "--set",
                                'faults.channels.PLANT_POSITION={"drop": 0.1}', "--set", "duration=2.0"])
        self.assertEqual(keywords, {"controller.kp": "controller__kp",
                                    "faults.channels.PLANT_POSITION": "faults__channels__PLANT_POSITION",
                                    "duration": "duration"})
        with self.assertRaisesRegex(lagrange.LagrangeError, "the value of duration \\(keyword duration\\) is not JSON"):
            lagrange.programs._sets({"duration": float("nan")})
        with self.assertRaisesRegex(lagrange.LagrangeError, "the value of controller.kp \\(keyword controller__kp\\)"):
            lagrange.programs._sets({"controller__kp": object()})

    def test_a_sweeps_jobs_that_is_no_number_is_refused(self):
        with self.assertRaisesRegex(lagrange.LagrangeError, "jobs='two': expected a whole number of runs at a time"):
            lagrange.sweep(self.scenario_file(), jobs="two")

    def test_a_sweeps_rows_are_read_as_the_cpp_readers_read_them(self):
        with tempfile.TemporaryDirectory() as d:
            rows = os.path.join(d, "sweep.jsonl")
            os.mkfifo(rows)
            said = isolated("import lagrange.programs as p\ntry:\n    p._rows(%r)\nexcept p.LagrangeError as e:\n"
                            "    print(e)\n" % d)
            self.assertEqual(said.strip(), "'%s' is a FIFO (named pipe); expected the sweep's rows (one JSON object "
                                           "a line, as lagrange sweep writes them) (a regular file)" % rows)
            os.unlink(rows)
            with open(rows, "w") as f:
                f.write('{"index": 1}\n\n{"index": 0}\n' + "[" * 100 + "]" * 100 + "\n")
            with self.assertRaisesRegex(lagrange.LagrangeError, "line 4 nests JSON deeper than 32 levels"):
                lagrange.programs._rows(d)
            with open(rows, "w") as f:
                f.write('{"index": 1}\n{"index": 0}\n')
            self.assertEqual(lagrange.programs._rows(d), [{"index": 0}, {"index": 1}])
            with open(rows, "w") as f:
                f.write('{"index": 0, "x": "%s"}\n' % ("y" * (64 << 10)))
            with self.assertRaisesRegex(lagrange.LagrangeError, "line 1 is longer than 65536 bytes"):
                lagrange.programs._rows(d)


if __name__ == "__main__":
    unittest.main()
