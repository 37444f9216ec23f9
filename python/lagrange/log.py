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
"""

import json
import os
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
        self.scan = None
        self.summary = None
        # summary.json's `verdict` as the run wrote it (docs/summary.md, "The
        # verdict"): {tracking, met, headline, reasons, warnings}; None when
        # there is no summary, or one written before verdicts existed.
        self.verdict = None
        self.scenario_yaml = None  # config.resolved.yaml's text
        self.scenario = None  # config.resolved.json as a dict (the same scenario; None for older runs)


def load(run_dir, numpy=None, verify=True):
    """Reads a run directory (OUT of `lagrange run`), or its run.lcm, as the
    lagrange subcommands take either (another log file alone: its events
    only, no summary or scenario beside it): run.lcm into per-channel columns,
    summary.json (None if absent), config.resolved.yaml as text
    (`scenario_yaml`) and config.resolved.json as a dict (`scenario`).
    numpy: None (use it when installed), True or False. verify: leave out
    (and count in `run.corrupt`) messages whose checksum does not match, as
    the project's own readers do; False skips the check (it is pure Python,
    about a second per 30 000 messages)."""
    if os.path.isfile(str(run_dir)):  # the log itself
        path = str(run_dir)
        run = Run(os.path.dirname(os.path.abspath(path)))
        # A run's folder holds its summary and scenario beside run.lcm; beside
        # another log (a stock lcm-logger's) they would be some other run's.
        return _load(run, path, numpy, verify, with_outputs=os.path.basename(path) == "run.lcm")
    run = Run(run_dir)
    return _load(run, os.path.join(run.dir, "run.lcm"), numpy, verify)


def _load(run, path, numpy, verify, with_outputs=True):
    if not os.path.exists(path):
        raise logfile.LogError("%s has no run.lcm; expected the output directory of a lagrange run (--out)" % run.dir)
    if numpy is None:
        try:
            import numpy as _numpy  # noqa: F401

            numpy = True
        except ImportError:
            numpy = False
    decoded = {}
    with logfile.LogReader(path, bounds=bounds_of_log(path)) as reader:
        for event in reader:
            if event.channel not in CHANNEL_TYPES:
                run.unknown_channels[event.channel] = run.unknown_channels.get(event.channel, 0) + 1
                continue
            msg = decode(event.channel, event.data)
            if msg is None:
                run.undecodable[event.channel] = run.undecodable.get(event.channel, 0) + 1
                continue
            header = getattr(msg, "header", None)
            if verify and header is not None and header.checksum != 0 and not contract.intact(msg):
                run.corrupt[event.channel] = run.corrupt.get(event.channel, 0) + 1
                continue
            decoded.setdefault(event.channel, []).append(msg)
        run.scan = reader.scan
    for channel, messages in decoded.items():
        if channel in PER_TICK:
            seen, once = set(), []
            for m in messages:  # one row per tick: the first copy (lockstep re-sends a tick unanswered in time)
                if m.header.tick in seen:
                    run.repeated[channel] = run.repeated.get(channel, 0) + 1
                    continue
                seen.add(m.header.tick)
                once.append(m)
            run.channels[channel] = _columns(once, numpy)
        else:
            run.messages[channel] = messages
    if not with_outputs:
        return run
    summary = os.path.join(run.dir, "summary.json")
    if os.path.exists(summary):
        with open(summary, "r", encoding="utf-8") as f:
            run.summary = json.load(f)
        if isinstance(run.summary, dict) and isinstance(run.summary.get("verdict"), dict):
            run.verdict = run.summary["verdict"]
    resolved = os.path.join(run.dir, "config.resolved.yaml")
    if os.path.exists(resolved):
        with open(resolved, "r", encoding="utf-8") as f:
            run.scenario_yaml = f.read()
    resolved_json = os.path.join(run.dir, "config.resolved.json")
    if os.path.exists(resolved_json):
        with open(resolved_json, "r", encoding="utf-8") as f:
            run.scenario = json.load(f)
    return run
