"""A controller of your own in a lagrange run (controller.type: external).

You write the law; this module keeps the contract of
docs/external_programs.md -- the run's LCM URL, id and key from the
environment, the MAC on every datagram, the header (run id, publisher, pid,
per-channel seq, checksum), which positions to accept, lockstep's re-sent
ticks (answered with the same command, the law never stepped twice on one
sample), the STATUS handshake ("ready" until the first position, "running",
"finished" when the plant finishes) -- in lockstep and in realtime alike.

    import lagrange.external

    def step(t, q):              # t: the sample's sim time [s]; q: the joint angles [rad]
        return [-20.0 * q[0], -5.0 * q[1]]      # u [N m], one per joint

    lagrange.external.run(step)

step may also return a dict: {"u": [...]} plus any of the diagnostics
"q_desired", "q_error", "theta", "filter_state" (one number per joint each;
the log, CSV export, plots and replay carry them). reset(), when given, is
called once before the first sample. See examples/external_controller/pd_controller.py.

The run's resolved scenario -- gains, reference, the arm's parameters, every
default filled in -- is scenario() (a dict; also Controller.scenario), read
from the JSON file LAGRANGE_CONFIG_JSON names, which `lagrange run` and
`lagrange replay` both hand over:

    s = lagrange.external.scenario()
    offset = s["reference"]["offset"]           # b_i [rad], one per joint
"""

import io
import json
import math
import os
import sys
import time

from . import contract
from .control_command_t import control_command_t
from .header_t import header_t
from .lcm import LCM, LCMError
from .loop_stats_t import loop_stats_t
from .plant_position_t import plant_position_t
from .status_t import status_t

_DIAGNOSTICS = ("q_desired", "q_error", "theta", "filter_state")
# Answers kept for re-sent ticks: lockstep re-sends only the tick it awaits.
_KEEP_ANSWERS = 64


class ContractError(RuntimeError):
    """The environment or the law broke the contract (named in the message)."""


def _environment(name, environ):
    value = environ.get(name)
    if not value:
        raise ContractError(
            "%s is not set: an external controller is started by `lagrange run` (controller.type: external), "
            "which sets LAGRANGE_LCM_URL, LAGRANGE_RUN_ID, LAGRANGE_KEY_FILE, LAGRANGE_CONFIG, "
            "LAGRANGE_CONFIG_JSON, LAGRANGE_JOINTS, LAGRANGE_MODE and LAGRANGE_CLOCK_OFFSET_US (`lagrange replay "
            "LOG -- COMMAND` sets the same)" % name)
    return value


def scenario(environ=None):
    """The run's resolved scenario as a dict (config.resolved.json, which
    LAGRANGE_CONFIG_JSON names): the same tree as config.resolved.yaml,
    numbers as numbers. Raises ContractError when the variable is unset or the
    file cannot be read."""
    path = _environment("LAGRANGE_CONFIG_JSON", os.environ if environ is None else environ)
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        raise ContractError("cannot read the run's scenario from LAGRANGE_CONFIG_JSON=%s: %s" % (path, e)) from None


class Controller:
    """The contract around a law step(t, q) -> u. Most users call run(step)."""

    def __init__(self, step, reset=None, environ=None):
        environ = os.environ if environ is None else environ
        self.step = step
        self.reset = reset
        self.url = _environment("LAGRANGE_LCM_URL", environ)
        self.run_id = int(_environment("LAGRANGE_RUN_ID", environ))
        self.joints = int(_environment("LAGRANGE_JOINTS", environ))
        self.mode = environ.get("LAGRANGE_MODE", "")
        self.key = contract.Key.from_file(_environment("LAGRANGE_KEY_FILE", environ))
        # The resolved scenario (a dict), when the program was started by lagrange.
        self.scenario = scenario(environ) if environ.get("LAGRANGE_CONFIG_JSON") else None
        self.headers = contract.Headers(self.run_id, "controller")
        self.lcm = LCM(self.url)
        self.answered = {}  # tick -> the command sent for it
        self.last_tick = -1
        self.plant_finished = False
        self.rejected = 0  # datagrams dropped: bad MAC, another run, corrupt, wrong size
        self.lcm.subscribe("PLANT_POSITION", self._on_position)
        self.lcm.subscribe("STATUS", self._on_status)

    # -- receiving -------------------------------------------------------
    def _message(self, kind, data):
        """The message and the bytes it was decoded from (for contract.intact), or (None, None)."""
        payload = self.key.authenticate(data)
        if payload is None:
            return None, None  # forged, altered or of another run: never decoded
        buf = io.BytesIO(payload)
        try:
            return kind.decode(buf), payload[:buf.tell()]
        except Exception:
            return None, None

    def _on_status(self, _channel, data):
        s, _ = self._message(status_t, data)
        if s is not None and s.header.run_id == self.run_id and s.process == "plant" and s.state == "finished":
            self.plant_finished = True

    def _on_position(self, _channel, data):
        p, encoding = self._message(plant_position_t, data)
        # The bytes decoded, hashed as they are: no second encoding per message.
        if (p is None or p.header.run_id != self.run_id or p.header.publisher != "plant"
                or not contract.intact(p, encoding)
                or p.num_joints != self.joints or len(p.q) != self.joints):
            self.rejected += 1
            return
        tick = p.header.tick
        cached = self.answered.get(tick)
        if cached is not None:  # a re-sent position: the same answer again, the law not stepped
            self._publish_command(cached)
            return
        if tick <= self.last_tick:
            return  # older than one answered: never step back
        if self.last_tick < 0 and self.reset is not None:
            self.reset()
        command = self._command(p)
        self.answered[tick] = command
        for old in [t for t in self.answered if t <= tick - _KEEP_ANSWERS]:  # ticks skipped in realtime too
            del self.answered[old]
        self.last_tick = tick
        self._publish_command(command)

    # -- the law ---------------------------------------------------------
    def _vector(self, what, value, p):
        try:
            v = [float(x) for x in value]
        except TypeError:
            raise ContractError("step() returned %s %r; expected %d numbers" % (what, value, self.joints)) from None
        if len(v) != self.joints:
            raise ContractError("step() returned %d numbers for %s; expected %d (one per joint)"
                                % (len(v), what, self.joints))
        for j, x in enumerate(v):
            if not math.isfinite(x):  # the plant would refuse the command and stall: say it here, at once
                raise ContractError("step() returned %r for %s[%d] (joint %d) at the sample of tick %d (t = %.6g s); "
                                    "expected finite numbers" % (x, what, j, j + 1, p.header.tick, p.header.sim_time))
        return v

    def _command(self, p):
        out = self.step(p.header.sim_time, list(p.q))
        fields = out if isinstance(out, dict) else {"u": out}
        if "u" not in fields:
            raise ContractError("step() returned a dict without \"u\"; expected {\"u\": [...], ...}")
        c = control_command_t()
        c.header = header_t()
        c.header.tick = p.header.tick
        c.header.sim_time = p.header.sim_time
        c.input_position_tick = p.header.tick
        c.input_actuator_tick = -1
        c.input_motor_tick = -1
        c.num_joints = self.joints
        c.u = self._vector("u", fields["u"], p)
        for name in _DIAGNOSTICS:
            setattr(c, name, self._vector(name, fields[name], p) if name in fields else [0.0] * self.joints)
        c.chain_order = 0
        c.xi_error = []
        return c

    # -- publishing ------------------------------------------------------
    def _publish(self, channel, msg):
        self.lcm.publish(channel, self.key.sign(contract.sealed_encoding(msg)))

    def _publish_command(self, c):
        self.headers.stamp(c.header, "CONTROL_COMMAND", c.header.tick, c.header.sim_time)
        self._publish("CONTROL_COMMAND", c)

    def publish_status(self, state):
        s = status_t()
        s.header = header_t()
        self.headers.stamp(s.header, "STATUS", max(self.last_tick, 0), 0.0)
        s.process = "controller"
        s.state = state
        s.last_tick = self.last_tick
        s.tracking_error = float("nan")
        s.message = ""
        s.num_channels = 0
        s.channels = []
        s.loop = loop_stats_t()
        s.loop.scheduler = ""
        self._publish("STATUS", s)

    def serve(self):
        """Answers positions until the plant says it has finished; then
        "finished" and returns 0."""
        next_status = 0.0
        while not self.plant_finished:
            now = time.monotonic()
            if now >= next_status:  # twice a second; ten times before the first position
                self.publish_status("ready" if self.last_tick < 0 else "running")
                next_status = now + (0.1 if self.last_tick < 0 else 0.5)
            self.lcm.handle_timeout(max(1, int((next_status - time.monotonic()) * 1000)))
        for _ in range(3):
            self.publish_status("finished")
        self.lcm.close()
        return 0


def run(step, reset=None):
    """Serves step(t, q) -> u as the run's controller until the run ends, then
    exits the program (0). Errors of the contract are printed and exit 1."""
    try:
        code = Controller(step, reset).serve()
    except (ContractError, ValueError, LCMError) as e:
        print("%s: %s" % (os.path.basename(sys.argv[0]) or "controller", e), file=sys.stderr)
        code = 1
    sys.exit(code)
