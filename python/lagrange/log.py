"""A run's outputs in Python: `load(run_dir)` reads OUT/run.lcm into
per-channel arrays, with summary.json and the resolved scenario beside them.

    import lagrange.log
    run = lagrange.log.load("runs/demo")
    truth = run.channels["PLANT_TRUTH"]
    truth["t"]            # header.sim_time of each sample [s]
    truth["q"]            # one row per sample, one column per joint (0-based, as in Python)
    truth["q"][k][1]      # joint 2's angle at sample k
    run.summary["tracking"]["final_error"]
    run.verdict["tracking"]  # "met", "NOT met" or "not judged"; run.verdict["reasons"] say why

Every event is first held to the largest its channel's message can be in the
log's scenario (lagrange/log_bounds.py): a larger one is skipped unread and
named in `run.scan.problems()`, never decoded.

Each channel is a dict of field name to column: scalars as a list (or a 1-D
numpy array), per-joint fields as a list of lists (or a 2-D numpy array, one
row per sample), header fields as "header.tick", ... and "t" for
"header.sim_time", one row per tick (the first copy of a tick lockstep
re-sent; `run.repeated` counts the others). numpy is used when it is installed, never required
(`numpy=False` turns it off). Messages that do not decode as their channel's
type, or whose checksum does not match (a damaged log, a copy corrupted on
the way and recorded as it arrived), are counted in `run.undecodable` and
`run.corrupt`, never returned.

Rows are the run's own: a per-tick row or a STATUS whose header claims a
tick outside the log's scenario's, 0 to round(duration * publish_rate)
(`run.bounds.last_tick`; log_bounds.py), is dropped before it is decoded and
counted in `run.out_of_range` (and said in `run.problems()`); a copy of a
tick already kept is counted in `run.repeated` and not kept. So what `load`
holds grows with the scenario, not with the file.

The true tracking error is `run.tracking` (see Run.tracking): per tick the
plant's true angles PLANT_TRUTH.q less the reference the controller tracked,
CONTROL_COMMAND.q_desired, joined by header.tick, with t = tick /
plant.publish_rate of the run's scenario:

    tr = run.tracking
    tr["t"], tr["q_error"], tr["error_norm"]    # [s], rows of q - q_d [rad], ||q - q_d|| [rad]
    tr.unjoined                                 # ticks found in one of the two channels only

numpy=True without numpy installed raises ModuleNotFoundError naming the
package to install (on Debian 12: python3-numpy).

Every file of the run is looked at before a byte is read, as the C++ readers
do: a FIFO, a device, a directory, a file of /proc or /sys, or a link to one
is refused, never waited on; summary.json is read whole only up to 16 MiB,
config.resolved.yaml and config.resolved.json up to the largest scenario a
log can hold (MAX_RESOLVED_BYTES), and JSON nested deeper than
MAX_JSON_DEPTH levels is refused before it is parsed. Every refusal is a
LogError (a ValueError) naming the file, what was wrong and what was
expected.
"""

import itertools
import json
import math
import operator
import os
import re
import struct

from . import contract, log_bounds, logfile
from .actuator_state_t import actuator_state_t
from .control_command_t import control_command_t
from .plant_motor_t import plant_motor_t
from .plant_position_t import plant_position_t
from .plant_rate_t import plant_rate_t
from .plant_truth_t import plant_truth_t
from .robot_description_t import robot_description_t
from .scenario_t import scenario_t
from .status_t import status_t

# transport/channels.hpp: each channel's one message type.
CHANNEL_TYPES = {
    "PLANT_POSITION": plant_position_t,
    "PLANT_TRUTH": plant_truth_t,
    "PLANT_MOTOR": plant_motor_t,
    "PLANT_RATE": plant_rate_t,
    "CONTROL_COMMAND": control_command_t,
    "ACTUATOR_STATE": actuator_state_t,
    "STATUS": status_t,
    "SCENARIO": scenario_t,
    "ROBOT_DESCRIPTION": robot_description_t,
}

# Channels whose messages are one sample each, read into columns.
PER_TICK = ("PLANT_POSITION", "PLANT_TRUTH", "PLANT_MOTOR", "PLANT_RATE", "CONTROL_COMMAND", "ACTUATOR_STATE")
# Channels whose messages start with a header (its tick just after the 8-byte fingerprint).
WITH_TICK = PER_TICK + ("STATUS",)

LogError = logfile.LogError

# summary.json: a few kB of metrics; 16 MiB is far beyond any run's (as
# `lagrange export` and `lagrange view` read it: tools/export/export.cpp).
MAX_SUMMARY_BYTES = 16 << 20
# config.resolved.yaml (and .json): the largest scenario a log can hold, a
# scenario file of 1 MiB resolved with its URDF inline (as export reads it).
MAX_RESOLVED_BYTES = log_bounds.MAX_SCENARIO_EVENT_BYTES
# JSON nesting, as the C++ reader of a sweep's rows bounds it
# (tools/sweep/sweep_files.hpp, kMaxSweepJsonDepth); a run's summary.json and
# config.resolved.json nest 6 levels at most.
MAX_JSON_DEPTH = 32


def decode(channel, data):
    """The message `data` holds on `channel`, or None when it is not one
    (a channel of no known type, a wrong fingerprint, a short buffer)."""
    kind = CHANNEL_TYPES.get(channel)
    if kind is None:
        return None
    try:
        return kind.decode(data)
    except (ValueError, struct.error, UnicodeDecodeError, IndexError, OverflowError, MemoryError):
        return None


def _columns(messages, use_numpy):
    """The fields of a list of messages of one type as columns."""
    if not messages:
        return {}
    out = {}
    first = messages[0]
    for name in first.__slots__:
        if name == "header":
            for h in first.header.__slots__:
                out["header." + h] = [getattr(m.header, h) for m in messages]
            continue
        value = getattr(first, name)
        if isinstance(value, (int, float, str, bytes)):
            out[name] = [getattr(m, name) for m in messages]
        elif isinstance(value, (list, tuple)) and all(isinstance(v, (int, float)) for v in value):
            out[name] = [list(getattr(m, name)) for m in messages]
        elif isinstance(value, (list, tuple)):  # arrays of arrays (xi_error) or of structs: as they are
            out[name] = [getattr(m, name) for m in messages]
        # nested structs other than the header: left out of the columns
    out["t"] = out["header.sim_time"]
    if use_numpy:
        import numpy

        for key, column in out.items():
            try:
                if column and isinstance(column[0], (int, float)):
                    out[key] = numpy.asarray(column)
                elif column and isinstance(column[0], list) and len({len(r) for r in column}) == 1:
                    out[key] = numpy.asarray(column, dtype=float)
            except (ValueError, TypeError):
                pass
    return out


def bounds_of_log(path):
    """How large each channel's events can be in the log at `path`: from its
    first SCENARIO that decodes (no other event's data is read), or the
    project's limits. Raises LogError when that SCENARIO is larger than any
    scenario can be."""
    with logfile.LogReader(path, only_channel="SCENARIO") as reader:
        for event in reader:
            if reader.scan.first_oversized:
                break
            message = decode(event.channel, event.data)
            if message is not None:
                return log_bounds.bounds_of_scenario(message.yaml)
        if reader.scan.first_oversized:
            _, offset, size, bound, _ = reader.scan.first_oversized[0]
            raise logfile.LogError("%s: the SCENARIO at byte %d holds %d bytes; a scenario is at most %d (a scenario "
                                   "file of at most 1 MiB resolved with its URDF inline); expected the log of a "
                                   "lagrange run" % (path, offset, size, bound))
    return log_bounds.bounds_of_scenario(None)


# A JSON string, to its closing quote or to the end of the text (so that a
# string left open never sends the search back over the rest: linear time).
_JSON_STRING = re.compile(r'"[^"\\]*(?:\\.[^"\\]*)*(?:"|\\?\Z)', re.S)
# Of a text's UTF-8 bytes, the brackets alone (every other byte deleted),
# an opening one as 2 and a closing one as 0: the level after the k-th
# bracket is the sum of the first k, less k.
_BRACKET_STEPS = bytes.maketrans(b"[{]}", b"\x02\x02\x00\x00")
_NOT_BRACKETS = bytes(b for b in range(256) if b not in b"[]{}")


def _deeper_than(text, limit):
    """Whether the JSON `text` nests deeper than `limit` levels, found
    without recursion and in time linear in the text (brackets inside
    strings do not count)."""
    if text.count("[") + text.count("{") <= limit:
        return False
    steps = _JSON_STRING.sub("", text).encode("utf-8", "surrogatepass").translate(_BRACKET_STEPS, _NOT_BRACKETS)
    return max(map(operator.sub, itertools.accumulate(steps), itertools.count(1)), default=0) > limit


def _text_of(path, max_bytes, expected):
    data = logfile.read_regular_file(path, max_bytes, expected)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise LogError("'%s' is not UTF-8 text (byte %d is not); expected %s" % (path, e.start, expected)) from None


def read_json(path, max_bytes, expected):
    """The JSON value in the file `path`, read as read_regular_file reads
    (a regular file of at most max_bytes), nested at most MAX_JSON_DEPTH
    levels. Raises LogError naming the file, what was wrong and `expected`."""
    return parse_json(_text_of(path, max_bytes, expected), "'%s'" % path, expected)


def parse_json(text, where, expected):
    """The JSON value `text` holds, nested at most MAX_JSON_DEPTH levels (the
    depth checked first, without recursion); else LogError saying `where`
    ("'OUT/summary.json'"), what was wrong and `expected`."""
    if _deeper_than(text, MAX_JSON_DEPTH):
        raise LogError("%s nests JSON deeper than %d levels; expected %s" % (where, MAX_JSON_DEPTH, expected))
    try:
        return json.loads(text)
    except RecursionError:  # not reached after the depth check; never let it out raw
        raise LogError("%s nests JSON too deeply; expected %s" % (where, expected)) from None
    except ValueError as e:  # JSONDecodeError, a number of more digits than Python converts
        raise LogError("%s is not JSON (%s); expected %s" % (where, e, expected)) from None


class Run:
    """A run's outputs (see the module's text)."""

    def __init__(self, run_dir):
        self.dir = str(run_dir)
        self.channels = {}  # channel -> {field: column}
        self.messages = {}  # channel -> [decoded messages], for STATUS, SCENARIO, ROBOT_DESCRIPTION
        self.undecodable = {}  # channel -> count
        self.repeated = {}  # channel -> messages of a tick already read (lockstep re-sends), left out
        self.corrupt = {}  # channel -> messages whose checksum does not match (recorded as they arrived), left out
        self.unknown_channels = {}  # channel -> count
        # channel -> rows (and STATUS) whose tick is not one of the scenario's, 0 to bounds.last_tick: left out
        self.out_of_range = {}
        self.first_out_of_range = []  # (channel, byte offset, tick), the first few
        self.bounds = None  # log_bounds.Bounds: each channel's largest event and the run's ticks
        self.scan = None
        self.summary = None
        # summary.json's `verdict` as the run wrote it (docs/summary.md, "The
        # verdict"): {tracking, met, headline, reasons, warnings}; None when
        # there is no summary, or one written before verdicts existed.
        self.verdict = None
        self.scenario_yaml = None  # config.resolved.yaml's text
        self.scenario = None  # config.resolved.json as a dict (the same scenario; None for older runs)
        self.numpy = False  # whether the columns are numpy arrays (load's `numpy`)
        self._tracking = None

    @property
    def tracking(self):
        """The true tracking error, one row per tick (a Tracking: a dict of
        columns, made on first use and kept):

            "tick"        header.tick of the row, ascending
            "t"           tick / plant.publish_rate of the run's scenario [s]
                          (the log's SCENARIO, else config.resolved.json or
                          .yaml beside it; never a sender's sim_time); None
                          when none of them gives the rate
            "q_error"     q - q_d per joint [rad]: PLANT_TRUTH.q (the plant's
                          true angles, not the sensor's reading) less
                          CONTROL_COMMAND.q_desired of the same tick (the
                          reference the controller tracked; a controller that
                          reports none sends zeros, and q_error is then q)
            "error_norm"  the Euclidean norm of q_error [rad]

        Columns are lists (1-D numpy arrays, and a 2-D one for q_error, when
        the run was loaded with numpy), as the channels' columns are. A tick
        with a row in only one of the two channels is not joined: counted
        per channel in `tracking.unjoined` ({"PLANT_TRUTH": n,
        "CONTROL_COMMAND": m}; a realtime controller skips a sample without
        fresh input, and a message left out as corrupt leaves its tick
        alone); one whose two rows hold different numbers of joints is
        counted in `tracking.mismatched`. `tracking.publish_rate` is the
        rate t is computed with (None when unknown).

        `lagrange report` writes TRACKING.csv against the scenario's
        reference evaluated at each sample (as summary.json judges); on a
        built-in controller's run the two agree (both are q_d at the tick's
        time)."""
        if self._tracking is None:
            self._tracking = _tracking_of(self)
        return self._tracking

    def problems(self):
        """Warnings for a person: the log's (scan.problems()) and the rows
        left out for a tick that is not the run's; empty when all was read."""
        out = list(self.scan.problems()) if self.scan is not None else []
        dropped = sum(self.out_of_range.values())
        if dropped:
            named = "; ".join("%s at byte %d (tick %d)" % row for row in self.first_out_of_range)
            more = "; ..." if dropped > len(self.first_out_of_range) else ""
            out.append("%d %s a tick outside the run's ticks 0 to %d (%s) and %s left out, never decoded (%s%s)"
                       % (dropped, "message claimed" if dropped == 1 else "messages claimed", self.bounds.last_tick,
                          self.bounds.ticks_origin, "was" if dropped == 1 else "were", named, more))
        return out


def load(run_dir, numpy=None, verify=True):
    """Reads a run directory (OUT of `lagrange run`), or its run.lcm, as the
    lagrange subcommands take either (another log file alone: its events
    only, no summary or scenario beside it): run.lcm into per-channel columns,
    summary.json (None if absent), config.resolved.yaml as text
    (`scenario_yaml`) and config.resolved.json as a dict (`scenario`).
    numpy: None (use it when installed), True or False. verify: leave out
    (and count in `run.corrupt`) messages whose checksum does not match, as
    the project's own readers do; False skips the check (it is pure Python,
    about a second per 30 000 messages). Raises LogError naming the file and
    what was wrong when a file of the run is not what a run writes (the
    module's text)."""
    given = str(run_dir)
    if os.path.isdir(given):
        run = Run(given)
        return _load(run, os.path.join(run.dir, "run.lcm"), numpy, verify)
    if not os.path.lexists(given):
        raise LogError("%s does not exist; expected the output directory of a lagrange run (--out) or its run.lcm"
                       % given)
    # The log itself (LogReader refuses a FIFO, a device, ... by what it is).
    run = Run(os.path.dirname(os.path.abspath(given)))
    # A run's folder holds its summary and scenario beside run.lcm; beside
    # another log (a stock lcm-logger's) they would be some other run's.
    return _load(run, given, numpy, verify, with_outputs=os.path.basename(given) == "run.lcm")


# Messages of a tick outside the run's named in run.problems(); the rest are counted.
_OUT_OF_RANGE_NAMED = 3


def _load(run, path, numpy, verify, with_outputs=True):
    if not os.path.lexists(path):
        raise LogError("%s has no run.lcm; expected the output directory of a lagrange run (--out)" % run.dir)
    if with_outputs:  # the small files first: a refusal comes at once, not after the log
        _load_outputs(run)
    if numpy is None:
        try:
            import numpy as _numpy  # noqa: F401

            numpy = True
        except ImportError:
            numpy = False
    elif numpy:
        _require_numpy("lagrange.log.load(numpy=True)")
    run.numpy = bool(numpy)
    run.bounds = bounds = bounds_of_log(path)
    fingerprints = {channel: kind._get_packed_fingerprint() for channel, kind in CHANNEL_TYPES.items()}
    decoded = {}
    kept_ticks = {}  # per-tick channel -> the ticks of its rows
    previous = {}  # channel without a tick -> (data, message): an identical copy shares the message
    with logfile.LogReader(path, bounds=bounds) as reader:
        for event in reader:
            channel, data = event.channel, event.data
            if channel not in CHANNEL_TYPES:
                run.unknown_channels[channel] = run.unknown_channels.get(channel, 0) + 1
                continue
            if channel in WITH_TICK:
                # The tick its header claims, before anything is decoded: one
                # that is not the run's is left out, whatever the rest holds.
                if len(data) >= 16 and data[:8] == fingerprints[channel]:
                    tick = struct.unpack_from(">q", data, 8)[0]
                    if not bounds.holds_tick(tick):
                        run.out_of_range[channel] = run.out_of_range.get(channel, 0) + 1
                        if len(run.first_out_of_range) < _OUT_OF_RANGE_NAMED:
                            run.first_out_of_range.append((channel, event.offset, tick))
                        continue
            else:
                same = previous.get(channel)
                if same is not None and same[0] == data:  # a scenario published again (a stock logger's)
                    decoded[channel].append(same[1])
                    continue
            msg = decode(channel, data)
            if msg is None:
                run.undecodable[channel] = run.undecodable.get(channel, 0) + 1
                continue
            header = getattr(msg, "header", None)
            if verify and header is not None and header.checksum != 0 and not contract.intact(msg):
                run.corrupt[channel] = run.corrupt.get(channel, 0) + 1
                continue
            if channel in PER_TICK:
                # One row per tick: the first copy (lockstep re-sends a tick unanswered in time).
                ticks = kept_ticks.setdefault(channel, set())
                if header.tick in ticks:
                    run.repeated[channel] = run.repeated.get(channel, 0) + 1
                    continue
                ticks.add(header.tick)
            elif channel not in WITH_TICK:
                previous[channel] = (data, msg)
            decoded.setdefault(channel, []).append(msg)
        run.scan = reader.scan
    for channel, messages in decoded.items():
        if channel in PER_TICK:
            run.channels[channel] = _columns(messages, numpy)
        else:
            run.messages[channel] = messages
    return run


def _load_outputs(run):
    """summary.json, config.resolved.yaml and config.resolved.json beside the
    log, each when it is there (a link is there, even one to nothing)."""
    summary = os.path.join(run.dir, "summary.json")
    if os.path.lexists(summary):
        run.summary = read_json(summary, MAX_SUMMARY_BYTES, "the run's summary.json")
        if isinstance(run.summary, dict) and isinstance(run.summary.get("verdict"), dict):
            run.verdict = run.summary["verdict"]
    resolved = os.path.join(run.dir, "config.resolved.yaml")
    if os.path.lexists(resolved):
        run.scenario_yaml = _text_of(resolved, MAX_RESOLVED_BYTES, "the run's resolved scenario")
    resolved_json = os.path.join(run.dir, "config.resolved.json")
    if os.path.lexists(resolved_json):
        run.scenario = read_json(resolved_json, MAX_RESOLVED_BYTES, "the run's resolved scenario as JSON")


def _require_numpy(what):
    """numpy, or ModuleNotFoundError saying which package installs it."""
    try:
        import numpy
    except ImportError:
        raise ModuleNotFoundError("%s: numpy is not installed; on Debian 12: sudo apt-get install python3-numpy "
                                  "(or pip install numpy); without numpy=True, load uses numpy only when it is "
                                  "there and returns lists otherwise" % what, name="numpy") from None
    return numpy


class Tracking(dict):
    """Run.tracking: the columns "tick", "t", "q" (PLANT_TRUTH.q), "q_desired"
    (CONTROL_COMMAND.q_desired), "q_error" (q - q_desired), "error_norm" and,
    for a run whose controller has a chain (CONTROL_COMMAND.chain_order > 0),
    "xi_error" (per tick, the chain's stage errors, one row per stage), with
    `unjoined` (per channel, ticks found in that channel only), `mismatched`
    (ticks whose two rows hold different numbers of joints) and
    `publish_rate` (what t is computed with, or None)."""

    def __init__(self, columns, unjoined, mismatched, publish_rate):
        super().__init__(columns)
        self.unjoined = unjoined
        self.mismatched = mismatched
        self.publish_rate = publish_rate


def _positive_rate(text):
    """A publish rate given as a number or its text, if finite and > 0."""
    try:
        rate = float(text)
    except (TypeError, ValueError, OverflowError):
        return None
    return rate if math.isfinite(rate) and rate > 0 else None


def _publish_rate_of(run):
    """plant.publish_rate of the run's scenario: the log's SCENARIO (the one
    its ticks are bounded by), else config.resolved.json, else .yaml."""
    for message in run.messages.get("SCENARIO", ())[:1]:
        rate = _positive_rate(log_bounds._section_value(message.yaml, "plant", "publish_rate"))
        if rate is not None:
            return rate
    plant = run.scenario.get("plant") if isinstance(run.scenario, dict) else None
    if isinstance(plant, dict) and not isinstance(plant.get("publish_rate"), bool):
        rate = _positive_rate(plant.get("publish_rate"))
        if rate is not None:
            return rate
    if run.scenario_yaml is not None:
        return _positive_rate(log_bounds._section_value(run.scenario_yaml, "plant", "publish_rate"))
    return None


def _tracking_of(run):
    truth = run.channels.get("PLANT_TRUTH") or {}
    command = run.channels.get("CONTROL_COMMAND") or {}
    truth_row = {int(tick): k for k, tick in enumerate(truth.get("header.tick", ()))}
    command_row = {int(tick): k for k, tick in enumerate(command.get("header.tick", ()))}
    both = sorted(truth_row.keys() & command_row.keys())
    unjoined = {"PLANT_TRUTH": len(truth_row) - len(both), "CONTROL_COMMAND": len(command_row) - len(both)}
    q, q_desired = truth.get("q", ()), command.get("q_desired", ())
    stages = command.get("xi_error", ())
    ticks, actuals, desireds, errors, norms, xi = [], [], [], [], [], []
    mismatched = 0
    for tick in both:
        actual, desired = q[truth_row[tick]], q_desired[command_row[tick]]
        if len(actual) != len(desired):
            mismatched += 1
            continue
        error = [float(a) - float(d) for a, d in zip(actual, desired)]
        ticks.append(tick)
        actuals.append([float(a) for a in actual])
        desireds.append([float(d) for d in desired])
        errors.append(error)
        norms.append(math.sqrt(math.fsum(e * e for e in error)))
        if len(stages) > command_row[tick]:
            xi.append([[float(v) for v in stage] for stage in stages[command_row[tick]]])
    rate = _publish_rate_of(run)
    columns = {"tick": ticks, "t": None if rate is None else [tick * (1.0 / rate) for tick in ticks], "q": actuals,
               "q_desired": desireds, "q_error": errors, "error_norm": norms}
    if any(xi):  # a chain: its stage errors beside the links' (none for theorem1, the baselines)
        columns["xi_error"] = xi
    if run.numpy:
        numpy = _require_numpy("Run.tracking")
        columns["tick"] = numpy.asarray(ticks, dtype=numpy.int64)
        columns["error_norm"] = numpy.asarray(norms, dtype=float)
        if rate is not None:
            columns["t"] = numpy.asarray(columns["t"], dtype=float)
        joints = {len(row) for row in errors}
        if len(joints) <= 1:  # one row per tick, one column per joint (rows of mixed lengths stay lists)
            for name in ("q", "q_desired", "q_error"):
                columns[name] = numpy.asarray(columns[name], dtype=float).reshape(len(errors), max(joints, default=0))
            shapes = {(len(rows), len(rows[0]) if rows else 0) for rows in xi}
            if "xi_error" in columns and len(shapes) == 1:  # ticks x stages x joints
                columns["xi_error"] = numpy.asarray(xi, dtype=float).reshape((len(xi),) + shapes.pop())
    return Tracking(columns, unjoined, mismatched, rate)
