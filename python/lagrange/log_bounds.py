"""The largest event an honest log can hold on each of lagrange's channels,
as the C++ readers bound them (logs/event_bounds.hpp), so that a larger one
is skipped unread instead of decoded: one ACTUATOR_STATE of 241 MB holding
30 million one-joint rows took `load` to 3.3 GB.

A log's SCENARIO says how big each per-tick message of the run is: the arm's
joints, the actuator's order (rows of xi) and the torque steps a tick (rows
of tau_applied). The bound of a channel is its message's encoded size with
those counts, a publisher name of up to MAX_PUBLISHER_BYTES and the 32-byte
MAC trailer a stock lcm-logger recording keeps; CONTROL_COMMAND with the most
stages of xi_error any controller reports (4). Without a SCENARIO, or one
that does not read, the project's limits bound the events: 16 joints, order
4, 100 000 torque steps a tick.

The SCENARIO also says which ticks the run has: 0 to round(duration *
plant.publish_rate) (config::Scenario::lastTick). A per-tick row or a STATUS
whose header claims a tick outside them is none of this run's, and
lagrange.log.load drops and counts it (`run.out_of_range`), so that what it
keeps grows with the scenario, not with the file: a 582 MB log of 3 million
ticks for a 1 001-tick scenario took it to a MemoryError at 3.8 GB. Without a
SCENARIO that gives them, the ticks are bounded by the project's limit of
10^8 samples a run (config/work_bounds.hpp, kMaxSamples).

The shape is read from the resolved scenario as lagrange writes it (block
style: `actuator:` then `  order: 2`, `initial_state:` then `  q: [...]`,
`duration: 1` at the top); the standard library has no YAML reader, and
these five keys are all the bounds need. A scenario written otherwise falls
back to the project's limits.
"""

import math
import re

MAX_PUBLISHER_BYTES = 64
MAC_BYTES = 32
MAX_ACTUATOR_ORDER = 4
# config/work_bounds.hpp: kMaxJoints, kMaxStepsPerSample.
MAX_JOINTS = 16
MAX_TORQUE_STEPS = 100000
# config/work_bounds.hpp, kMaxSamples: samples (ticks) of one run; 1e8 is 28 hours at 1 kHz.
MAX_SAMPLES = 10 ** 8
# A scenario file (1 MiB) resolved with its URDF inline (16 MiB, escaped: twice that), and room.
MAX_SCENARIO_EVENT_BYTES = (1 << 20) + 2 * (16 << 20) + (64 << 10)
MAX_DESCRIPTION_EVENT_BYTES = 1 << 20
MAX_STATUS_EVENT_BYTES = 64 << 10


class Shape:
    """The counts that size a run's per-tick messages."""

    def __init__(self, joints, chain_order, torque_steps):
        self.joints = joints
        self.chain_order = chain_order
        self.torque_steps = torque_steps

    def describe(self):
        return "%d joint%s, actuator order %d, %d torque step%s a tick" % (
            self.joints, "" if self.joints == 1 else "s", self.chain_order, self.torque_steps,
            "" if self.torque_steps == 1 else "s")


PROJECT_LIMITS = Shape(MAX_JOINTS, MAX_ACTUATOR_ORDER, MAX_TORQUE_STEPS)

# LCM's encoding: a top-level message starts with its 8-byte fingerprint; a
# string is its int32 length, its bytes and a NUL.
_FINGERPRINT = 8
_HEADER = 8 + 8 + 8 + 8 + (4 + MAX_PUBLISHER_BYTES + 1) + 4 + 8 + 8


def encoded_sizes(shape):
    """Each per-tick channel's largest encoded message (no MAC trailer)."""
    n, m, steps = shape.joints, shape.chain_order, shape.torque_steps
    position = _FINGERPRINT + _HEADER + 4 + 8 * n
    return {
        "PLANT_POSITION": position,
        "PLANT_RATE": position,
        "PLANT_TRUTH": _FINGERPRINT + _HEADER + 4 + 3 * 8 * n + 3 * 8 + 8 + 1,
        "PLANT_MOTOR": _FINGERPRINT + _HEADER + 4 + 8 * n + 4 + 8 * n,
        "CONTROL_COMMAND": _FINGERPRINT + _HEADER + 3 * 8 + 4 + 5 * 8 * n + 4 + 8 * MAX_ACTUATOR_ORDER * n,
        "ACTUATOR_STATE": _FINGERPRINT + _HEADER + 8 + 4 + 4 + 8 * n + 4 + 8 * steps * n + n + 8 * m * n,
    }


class Bounds:
    """Per channel, the most data an event may hold in one log; `origin`
    says whose shape that is, for warnings. The run's ticks are 0 to
    `last_tick` (default: the project's limit), `ticks_origin` says whose."""

    def __init__(self, shape, origin, last_tick=None, ticks_origin=None):
        self.shape = shape
        self.origin = origin
        self.last_tick = MAX_SAMPLES if last_tick is None else last_tick
        self.ticks_origin = ticks_origin or "the project's limit of %d samples a run" % MAX_SAMPLES
        self.largest = {channel: size + MAC_BYTES for channel, size in encoded_sizes(shape).items()}
        self.largest.update({"STATUS": MAX_STATUS_EVENT_BYTES, "SCENARIO": MAX_SCENARIO_EVENT_BYTES,
                             "ROBOT_DESCRIPTION": MAX_DESCRIPTION_EVENT_BYTES})

    def largest_data(self, channel):
        """The most data bytes an event on `channel` may hold; None: no bound
        (a channel of another program, never decoded)."""
        return self.largest.get(channel)

    def holds_tick(self, tick):
        """Whether `tick` is one of the run's: 0 to last_tick."""
        return 0 <= tick <= self.last_tick


def project_limits(why="no scenario"):
    return Bounds(PROJECT_LIMITS, "%s: the project's limits (%s)" % (why, PROJECT_LIMITS.describe()), None,
                  "%s: the project's limit of %d samples a run" % (why, MAX_SAMPLES))


def _top_value(yaml, key):
    """`key`'s text at the top level of a block-style YAML map, or None."""
    value = re.search(r"^%s:[ \t]*(.*?)[ \t]*$" % re.escape(key), yaml, re.M)
    return value.group(1) if value else None


def _section_value(yaml, section, key):
    """`key`'s text in the top-level `section` of a block-style YAML map, or None."""
    match = re.search(r"^%s:[ \t]*\n((?:[ \t]+.*\n?|\n)*)" % re.escape(section), yaml, re.M)
    if match is None:
        return None
    value = re.search(r"^  %s:[ \t]*(.*?)[ \t]*$" % re.escape(key), match.group(1), re.M)
    return value.group(1) if value else None


def shape_of_scenario(yaml):
    """The shape the resolved scenario `yaml` gives, or None when a key is
    missing or not as lagrange writes it."""
    q = _section_value(yaml, "initial_state", "q")
    order = _section_value(yaml, "actuator", "order")
    rate = _section_value(yaml, "actuator", "rate")
    publish_rate = _section_value(yaml, "plant", "publish_rate")
    if None in (q, order, rate, publish_rate) or not (q.startswith("[") and q.endswith("]")):
        return None
    try:
        items = [item for item in q[1:-1].split(",") if item.strip()]
        joints, chain_order = len(items), int(order)
        steps = int(round(float(rate) / float(publish_rate)))
    except (ValueError, ZeroDivisionError, OverflowError):
        return None
    if not (1 <= joints <= MAX_JOINTS and 0 <= chain_order <= MAX_ACTUATOR_ORDER and 1 <= steps <= MAX_TORQUE_STEPS):
        return None
    return Shape(joints, chain_order, steps)


def _llround(x):
    """C's llround for x >= 0: halves away from zero (x - floor(x) is exact)."""
    whole = math.floor(x)
    return int(whole) + (1 if x - whole >= 0.5 else 0)


def last_tick_of_scenario(yaml):
    """The run's last tick, round(duration * plant.publish_rate) as
    config::Scenario::lastTick computes it, or None when a key is missing,
    not a number, or the product is not 0 to MAX_SAMPLES."""
    duration = _top_value(yaml, "duration")
    publish_rate = _section_value(yaml, "plant", "publish_rate")
    if duration is None or publish_rate is None:
        return None
    try:
        samples = float(duration) * float(publish_rate)
    except ValueError:
        return None
    if not (math.isfinite(samples) and 0 <= samples <= MAX_SAMPLES):
        return None
    return _llround(samples)


def bounds_of_scenario(yaml):
    """The bounds of a log whose SCENARIO holds `yaml` (None: no SCENARIO)."""
    if yaml is None:
        return project_limits("no SCENARIO in the log")
    last_tick = last_tick_of_scenario(yaml)
    if last_tick is not None:
        ticks_origin = "the log's scenario: duration %s s at plant.publish_rate %s Hz" % (
            _top_value(yaml, "duration"), _section_value(yaml, "plant", "publish_rate"))
    else:
        ticks_origin = ("the log's SCENARIO gives no duration and plant.publish_rate as lagrange writes them: the "
                        "project's limit of %d samples a run" % MAX_SAMPLES)
    shape = shape_of_scenario(yaml)
    if shape is None:
        bounds = project_limits("the log's SCENARIO is not a scenario as lagrange writes it")
        return Bounds(bounds.shape, bounds.origin, last_tick, ticks_origin)
    return Bounds(shape, "the log's scenario (%s)" % shape.describe(), last_tick, ticks_origin)
