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

The shape is read from the resolved scenario as lagrange writes it (block
style: `actuator:` then `  order: 2`, `initial_state:` then `  q: [...]`);
the standard library has no YAML reader, and these four keys are all the
bounds need. A scenario written otherwise falls back to the project's limits.
"""

import re

MAX_PUBLISHER_BYTES = 64
MAC_BYTES = 32
MAX_ACTUATOR_ORDER = 4
# config/work_bounds.hpp: kMaxJoints, kMaxStepsPerSample.
MAX_JOINTS = 16
MAX_TORQUE_STEPS = 100000
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
    says whose shape that is, for warnings."""

    def __init__(self, shape, origin):
        self.shape = shape
        self.origin = origin
        self.largest = {channel: size + MAC_BYTES for channel, size in encoded_sizes(shape).items()}
        self.largest.update({"STATUS": MAX_STATUS_EVENT_BYTES, "SCENARIO": MAX_SCENARIO_EVENT_BYTES,
                             "ROBOT_DESCRIPTION": MAX_DESCRIPTION_EVENT_BYTES})

    def largest_data(self, channel):
        """The most data bytes an event on `channel` may hold; None: no bound
        (a channel of another program, never decoded)."""
        return self.largest.get(channel)


def project_limits(why="no scenario"):
    return Bounds(PROJECT_LIMITS, "%s: the project's limits (%s)" % (why, PROJECT_LIMITS.describe()))


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


def bounds_of_scenario(yaml):
    """The bounds of a log whose SCENARIO holds `yaml` (None: no SCENARIO)."""
    if yaml is None:
        return project_limits("no SCENARIO in the log")
    shape = shape_of_scenario(yaml)
    if shape is None:
        return project_limits("the log's SCENARIO is not a scenario as lagrange writes it")
    return Bounds(shape, "the log's scenario (%s)" % shape.describe())
