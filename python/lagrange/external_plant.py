"""A plant of your own in a lagrange run (plant.type: external): a simulator
you wrote, or a bridge to a real arm (docs/hardware.md).

You write how the arm moves; this module keeps the plant's side of the
contract of docs/external_programs.md -- the run's LCM URL, id and key from
the environment, the MAC and header on every datagram, the run's clock
(lockstep: a tick goes out once the logger is at most lockstep.logger_window
behind, its measurements re-sent until the actuator answers, unconfirmed
ticks re-sent to the logger; realtime: a fixed-rate loop with the scenario's
stale-torque policy), PLANT_POSITION and PLANT_TRUTH of every tick, and the
STATUS handshake ("ready", "running", "finished" three times) -- and the
guards a bridge needs: torque, position and rate limits, and a watchdog (realtime
only: in lockstep waiting is the protocol).

    import lagrange.external_plant

    def step(t, u, dt):          # apply u [N m] from t for dt seconds
        ...                      # integrate, or command the arm and read it back
        return q, qdot           # at t + dt: joint angles [rad], rates [rad/s]

    lagrange.external_plant.run(step)

step may also return a dict {"q": [...], "qdot": [...]} with the arm's
"kinetic_energy" and "potential_energy" [J] (logged in PLANT_TRUTH; NaN,
"not known", when not given). The state at t = 0 is initial() when given
(a bridge reads the arm), else the scenario's initial_state. The resolved
scenario is Plant.scenario (a dict). See examples/external_plant/.
"""

import io
import math
import os
import signal
import sys
import time
import traceback

from . import contract
from .actuator_state_t import actuator_state_t
from .external import ContractError, _environment, scenario as _scenario
from .header_t import header_t
from .lcm import LCM, LCMError
from .loop_stats_t import loop_stats_t
from .plant_position_t import plant_position_t
from .plant_truth_t import plant_truth_t
from .status_t import status_t

TORQUE_COMMANDED = plant_truth_t.TORQUE_COMMANDED
TORQUE_HELD = plant_truth_t.TORQUE_HELD
TORQUE_ZERO = plant_truth_t.TORQUE_ZERO

# A realtime period's reading of what arrived: DRAIN_LATE datagrams even when
# the loop is behind schedule (one ACTUATOR_STATE a period and a few STATUS
# fit many times over), up to DRAIN_MAX while the period lasts.
DRAIN_LATE = 64
DRAIN_MAX = 1000
# Publication times of the recent positions, for the latency (a ring, as the
# built-in plant's).
_LATENCY_RING = 4096


class PlantStopped(RuntimeError):
    """The plant ended the run: a stall (whom it waited for), a limit crossed."""


class Limits:
    """What a bridge enforces whatever the controller asks (docs/hardware.md):
    torque: |u_i| <= torque[i] [N m], a larger command clipped (counted);
    position: lower[i] <= q_i <= upper[i] [rad], as [(lower, upper), ...];
    rate: |qdot_i| <= rate[i] [rad/s].
    A measured state outside its position or rate limits stops the run:
    zero torque, brake() when given, STATUS "failed" naming joint, value,
    limit and tick, exit 1. None: no limit of that kind."""

    def __init__(self, torque=None, position=None, rate=None):
        try:
            self.torque = None if torque is None else [float(x) for x in torque]
            self.rate = None if rate is None else [float(x) for x in rate]
        except (TypeError, ValueError):
            raise ContractError("Limits: torque and rate are one number per joint; got %r and %r"
                                % (torque, rate)) from None
        try:
            self.position = None if position is None else [(float(lo), float(hi)) for lo, hi in position]
        except (TypeError, ValueError):
            raise ContractError("Limits: position is one (lower, upper) pair per joint, e.g. [(-2.8, 2.8), "
                                "(-1.7, 1.7)]; got %r" % (position,)) from None
        for what, values in (("torque", self.torque), ("rate", self.rate)):
            if values is not None and not all(v > 0.0 for v in values):
                raise ContractError("Limits: every %s limit must be > 0; got %r" % (what, values))
        if self.position is not None and not all(lo < hi for lo, hi in self.position):
            raise ContractError("Limits: every position limit must be (lower, upper) with lower < upper; got %r"
                                % (self.position,))

    def check_sizes(self, joints):
        for what, values in (("torque", self.torque), ("position", self.position), ("rate", self.rate)):
            if values is not None and len(values) != joints:
                raise ContractError("Limits: %d %s limits for %d joints; expected one per joint"
                                    % (len(values), what, joints))

    def clip(self, u):
        """u within the torque limits, and whether any entry was clipped."""
        if self.torque is None:
            return list(u), False
        out = [max(-lim, min(lim, x)) for x, lim in zip(u, self.torque)]
        return out, out != list(u)

    def breach(self, q, qdot):
        """What the state crosses, as a sentence, or None."""
        for j in range(len(q)):
            if self.position is not None:
                lo, hi = self.position[j]
                if not lo <= q[j] <= hi:
                    return ("joint %d's position %.6g rad is outside its limits [%.6g, %.6g]"
                            % (j + 1, q[j], lo, hi))
            if self.rate is not None and not abs(qdot[j]) <= self.rate[j]:
                return "joint %d's rate %.6g rad/s is beyond its limit %.6g" % (j + 1, qdot[j], self.rate[j])
        return None


class TorqueChoice:
    """Which torque a realtime plant applies over the period after tick k
    (the built-in plant's rule, plant/plant_loops.cpp): the newest answer
    while at most max_age ticks old; then, under stale_torque "hold", that
    torque for hold_periods more; then zero. The watchdog (watchdog_periods,
    None: off) zeroes an answer older than that whatever the policy, and
    trips once per silence."""

    def __init__(self, max_age, hold_periods, hold, watchdog_periods=None):
        self.max_age = max_age
        self.hold_limit = max_age + hold_periods if hold else max_age
        self.watchdog = watchdog_periods
        self.held = self.zeroed = self.watchdog_trips = 0
        self.tripped = False

    def choose(self, k, newest_tick, newest_tau, joints):
        """(tau, source, input_tick, tripped_now) for the period after tick k."""
        age = k - newest_tick if newest_tick is not None else k + 1
        if self.watchdog is not None and age > self.watchdog:
            tripped_now = not self.tripped
            if tripped_now:
                self.watchdog_trips += 1
            self.tripped = True
            if k > 0:
                self.zeroed += 1
            return [0.0] * joints, TORQUE_ZERO, -1, tripped_now
        self.tripped = False
        if newest_tick is not None and age <= self.max_age:
            return list(newest_tau), TORQUE_COMMANDED, newest_tick, False
        if newest_tick is not None and age <= self.hold_limit:
            self.held += 1
            return list(newest_tau), TORQUE_HELD, newest_tick, False
        if k > 0:  # nothing can have answered before the first sample
            self.zeroed += 1
        return [0.0] * joints, TORQUE_ZERO, -1, False


_NAN = float("nan")


class _Histogram:
    """Percentiles of non-negative durations in fixed memory (1 % buckets).
    NaN while empty: loop_stats_t says "not measured" so, never 0 s."""

    _STEP = math.log(1.01)

    def __init__(self):
        self.counts = {}
        self.n = 0
        self.max = _NAN

    def add(self, seconds):
        b = int(math.log1p(max(0.0, seconds) * 1e7) / self._STEP)
        self.counts[b] = self.counts.get(b, 0) + 1
        self.n += 1
        if not seconds <= self.max:  # also the first (max NaN)
            self.max = seconds

    def percentile(self, p):
        if self.n == 0:
            return _NAN
        want, seen = p * self.n, 0
        for b in sorted(self.counts):
            seen += self.counts[b]
            if seen >= want:
                return math.expm1(b * self._STEP) * 1e-7
        return self.max


class Plant:
    """The contract around step(t, u, dt) -> q, qdot. Most users call run(step)."""

    def __init__(self, step, initial=None, limits=None, watchdog_periods=None, brake=None, environ=None):
        environ = os.environ if environ is None else environ
        self.step = step
        self.brake = brake
        self.limits = limits
        self.url = _environment("LAGRANGE_LCM_URL", environ)
        self.run_id = int(_environment("LAGRANGE_RUN_ID", environ))
        self.joints = int(_environment("LAGRANGE_JOINTS", environ))
        try:
            self.key = contract.Key.from_file(_environment("LAGRANGE_KEY_FILE", environ))
        except ValueError as e:
            raise ContractError(str(e)) from None
        self.scenario = _scenario(environ)
        s = self.scenario
        try:
            self.mode = s["mode"]
            self.rate = float(s["plant"]["publish_rate"])
            self.last_tick = int(round(float(s["duration"]) * self.rate))
            ls, rt = s["lockstep"], s["realtime"]
            self.retransmit = float(ls["retransmit_timeout"])
            self.window = int(ls["logger_window"])
            self.stall = float(ls["stall_timeout"])
            self.choice = TorqueChoice(int(rt["max_torque_age"]), int(rt["hold_periods"]),
                                       rt["stale_torque"] == "hold", watchdog_periods)
        except (KeyError, TypeError, ValueError) as e:
            raise ContractError("the run's scenario lacks %s; expected the resolved scenario lagrange wrote" % e)
        if watchdog_periods is not None and (isinstance(watchdog_periods, bool) or
                                             not (isinstance(watchdog_periods, int) and watchdog_periods >= 1)):
            raise ContractError("watchdog_periods must be a whole number of periods >= 1; got %r"
                                % (watchdog_periods,))
        if limits is not None:
            limits.check_sizes(self.joints)
        self.period = 1.0 / self.rate
        self.startup = 3.0 * self.stall  # plant/plant_loops.hpp startupTimeout
        self.energy = (float("nan"), float("nan"))  # not known until a state gives them
        if initial is not None:
            q, qdot = self._state(initial(), "initial()")  # with its energies, when it gives them
        else:
            q = [float(x) for x in s["initial_state"]["q"]]
            qdot = [float(x) for x in s["initial_state"]["qdot"]]
        self.q, self.qdot = q, qdot
        self.headers = contract.Headers(self.run_id, "plant")
        self.lcm = LCM(self.url)
        self.lcm.subscribe("ACTUATOR_STATE", self._on_actuator_state)
        self.lcm.subscribe("STATUS", self._on_status)
        self.peers = {}  # process -> (state, last_tick) of its newest STATUS
        self.logger_tick = None  # None: the logger not heard yet
        self.awaited, self.answer = -1, None  # lockstep: the tick awaited and its answer's torque
        self.newest = None  # (tick, tau) of the newest ACTUATOR_STATE
        self.newest_utime = 0  # its publish_utime (the run's clock)
        # Realtime's end-to-end latency, as the built-in plant measures it:
        # from publishing a position to receiving the actuator state of its tick.
        self.latencies = _Histogram()
        self._published = [None] * _LATENCY_RING  # (tick, publish_utime) of each tick's first position
        self.rejected = {}  # why -> how many datagrams dropped
        self.retransmits = self.log_resends = self.clipped = 0
        self.stop_signal = None
        self.resumed = False
        self.step_seconds = 0.0  # how long the last step() took [s]
        # Realtime: the time a period takes besides step() (this module's own
        # cost: messages, MACs, the rule) and step()'s, said at the end [s].
        self.own_cost, self.step_cost = _Histogram(), _Histogram()
        self.braked_at_stop = False

    # -- receiving -------------------------------------------------------
    def _reject(self, why):
        self.rejected[why] = self.rejected.get(why, 0) + 1

    def _message(self, kind, data):
        payload = self.key.authenticate(data)
        if payload is None:
            self._reject("MAC")  # forged, altered or of another run: never decoded
            return None
        buf = io.BytesIO(payload)
        try:
            m = kind.decode(buf)
        except Exception:
            self._reject("undecodable")
            return None
        if m.header.run_id != self.run_id:
            self._reject("another run")
            return None
        # The bytes decoded, hashed as they are: no second encoding per message.
        if not contract.intact(m, payload[:buf.tell()]):
            self._reject("checksum")
            return None
        return m

    def _on_status(self, _channel, data):
        s = self._message(status_t, data)
        if s is None or s.process == "plant":
            return
        self.peers[s.process] = (s.state, s.last_tick)
        if s.process == "logger":
            self.logger_tick = s.last_tick if self.logger_tick is None else max(self.logger_tick, s.last_tick)

    def _on_actuator_state(self, _channel, data):
        a = self._message(actuator_state_t, data)
        if a is None:
            return
        if a.header.publisher != "actuator":
            return self._reject("not the actuator's")
        if a.num_joints != self.joints or a.torque_steps != 1 or len(a.tau_applied) != 1 \
                or len(a.tau_applied[0]) != self.joints:
            return self._reject("wrong size")
        tau = list(a.tau_applied[0])
        if not all(math.isfinite(x) for x in tau):
            return self._reject("non-finite torque (NaN or Inf) from %s" % a.header.publisher)
        if a.header.tick == self.awaited and self.answer is None:
            self.answer = tau  # lockstep: the first state of the awaited tick; a stale or repeated one is ignored
        if self.newest is None or a.header.tick > self.newest[0]:
            self.newest = (a.header.tick, tau)  # realtime: the newest, whichever tick
            self.newest_utime = a.header.publish_utime
            sent = self._published[a.header.tick % _LATENCY_RING] if a.header.tick >= 0 else None
            if sent is not None and sent[0] == a.header.tick:
                # LCM's receive time (wall clock) against the run's clock, as plant/plant_loops.cpp does.
                self.latencies.add(max(0, self.lcm.recv_utime - sent[1]) * 1e-6)

    def _handle(self, timeout_ms):
        self.lcm.handle_timeout(max(0, int(timeout_ms)))

    def _drain(self, until):
        """What has arrived, without waiting: at least DRAIN_LATE datagrams
        whatever the time -- a loop behind schedule must still read the
        actuator's newest torque, or the torque goes stale while it is on the
        socket --, then more while before `until` (time.monotonic()), at most
        DRAIN_MAX: a flood of forged datagrams, each refused by its MAC, must
        not hold the loop (the built-in node's bound, transport/lcm_node.hpp).
        Returns how many were handled."""
        handled = 0
        while handled < DRAIN_MAX:
            if handled >= DRAIN_LATE and time.monotonic() >= until:
                break
            if self.lcm.handle_timeout(0) <= 0:
                break
            handled += 1
        return handled

    # -- the arm ---------------------------------------------------------
    def _state(self, out, what):
        fields = out if isinstance(out, dict) else None
        try:
            q, qdot = (fields["q"], fields["qdot"]) if fields is not None else out
            q, qdot = [float(x) for x in q], [float(x) for x in qdot]
        except (TypeError, ValueError, KeyError):
            raise ContractError("%s returned %r; expected (q, qdot) or {\"q\": [...], \"qdot\": [...]}, %d numbers "
                                "each" % (what, out, self.joints)) from None
        for name, v in (("q", q), ("qdot", qdot)):
            if len(v) != self.joints:
                raise ContractError("%s returned %d numbers for %s; expected %d (one per joint)"
                                    % (what, len(v), name, self.joints))
            for j, x in enumerate(v):
                if not math.isfinite(x):
                    raise ContractError("%s returned %r for %s of joint %d; expected finite numbers"
                                        % (what, x, name, j + 1))
        energy = []
        for name in ("kinetic_energy", "potential_energy"):  # each state its own; NaN: not known
            value = fields.get(name) if fields is not None else None
            try:
                value = float("nan") if value is None else float(value)
            except (TypeError, ValueError):
                raise ContractError("%s returned %r for %s; expected a number [J]" % (what, value, name)) from None
            if math.isinf(value):
                raise ContractError("%s returned %r for %s; expected a finite number, or none (not known)"
                                    % (what, value, name))
            energy.append(value)
        self.energy = tuple(energy)
        return q, qdot

    def _advance(self, k, tau):
        t = k * self.period
        u, clipped = self.limits.clip(tau) if self.limits is not None else (list(tau), False)
        self.clipped += 1 if clipped else 0
        began = time.perf_counter()
        out = self.step(t, u, self.period)
        self.step_seconds = time.perf_counter() - began  # the arm's share of the period, apart from ours
        self.q, self.qdot = self._state(out, "step() at t = %.6g s" % t)
        return u

    def _check_limits(self, k):
        why = self.limits.breach(self.q, self.qdot) if self.limits is not None else None
        if why is not None:
            raise PlantStopped("%s at tick %d (t = %.6g s); the plant stopped the run (its limits)"
                               % (why, k, k * self.period))

    def safe_stop(self):
        """Every end but "finished": brake() once, when given -- a bridge's
        own way to make the arm safe (zero torque, the brakes). Says so."""
        if self.brake is None or self.braked_at_stop:
            return
        self.braked_at_stop = True
        print("plant: calling brake()", file=sys.stderr, flush=True)
        self.brake()

    # -- publishing ------------------------------------------------------
    def _publish(self, channel, msg, tick, sim_time):
        self.headers.stamp(msg.header, channel, tick, sim_time)
        self.lcm.publish(channel, self.key.sign(contract.sealed_encoding(msg)))

    def _sample(self, k, tau, source, input_tick):
        t = k * self.period
        p = plant_position_t()
        p.header = header_t()
        p.num_joints = self.joints
        p.q = list(self.q)
        tr = plant_truth_t()
        tr.header = header_t()
        tr.num_joints = self.joints
        tr.q, tr.qdot, tr.tau_applied = list(self.q), list(self.qdot), list(tau)
        tr.kinetic_energy, tr.potential_energy = self.energy
        tr.total_energy = tr.kinetic_energy + tr.potential_energy
        tr.input_actuator_tick = input_tick
        tr.torque_source = source
        return k, t, p, tr

    def _send(self, sample, truth=True):
        k, t, p, tr = sample
        self._publish("PLANT_POSITION", p, k, t)
        slot = k % _LATENCY_RING
        sent = self._published[slot]
        if sent is None or sent[0] != k:  # the first copy: a re-sent one is not what was answered first
            self._published[slot] = (k, p.header.publish_utime)
        if truth:
            self._publish("PLANT_TRUTH", tr, k, t)

    def publish_status(self, state, last_tick, message="", loop=None):
        s = status_t()
        s.header = header_t()
        s.process = "plant"
        s.state = state
        s.last_tick = last_tick
        s.tracking_error = float("nan")
        s.message = message
        s.num_channels = 0
        s.channels = []
        s.loop = loop if loop is not None else loop_stats_t()
        if loop is None:
            s.loop.scheduler = ""
        self._publish("STATUS", s, max(last_tick, 0), max(last_tick, 0) * self.period)

    # -- what went wrong -------------------------------------------------
    def _heard(self):
        peers = ", ".join("%s %s at tick %d" % (p, st, tick) for p, (st, tick) in sorted(self.peers.items()))
        rejected = ", ".join("%d (%s)" % (n, why) for why, n in sorted(self.rejected.items()))
        return "heard: %s; rejected datagrams: %s" % (peers or "nobody", rejected or "none")

    def _stalled(self, what, k, waited):
        return PlantStopped("stalled at tick %d: %s for %.1f s (lockstep.stall_timeout %g s); %s"
                            % (k, what, waited, self.stall, self._heard()))

    def _stop_requested(self):
        return self.stop_signal is not None

    def _take_resume(self):
        resumed, self.resumed = self.resumed, False
        return resumed

    # -- lockstep --------------------------------------------------------
    def _resend_for_logger(self, unconfirmed, now, resend_at):
        if self.logger_tick is None or now < resend_at:
            return resend_at
        for k in [t for t in unconfirmed if t <= self.logger_tick]:
            del unconfirmed[k]
        for k in sorted(unconfirmed):
            self._send(unconfirmed[k])
            self.log_resends += 1
        return now + self.retransmit

    def serve_lockstep(self):
        self.publish_status("ready", -1)
        unconfirmed = {}  # tick -> its sample, until the logger confirms it
        tau, source, input_tick = [0.0] * self.joints, TORQUE_ZERO, -1
        next_status = time.monotonic()
        if self.choice.watchdog is not None:
            # Waiting is lockstep's protocol: an answer late by scheduling is no
            # silence of the controller's, and a brake there would be one the
            # summary never counts. lockstep.stall_timeout ends a run that stalls.
            print("plant: watchdog_periods=%d applies in realtime only; in lockstep the plant waits for each answer "
                  "(lockstep.stall_timeout %g s ends a stalled run)" % (self.choice.watchdog, self.stall),
                  file=sys.stderr, flush=True)
        for k in range(self.last_tick + 1):
            wait_start = time.monotonic()
            resend_at, resumed = wait_start + self.retransmit, False
            while not (self.logger_tick is not None and k - self.logger_tick <= self.window):
                if self._stop_requested():
                    self.publish_status("interrupted", k - 1)
                    return 0
                if self._take_resume():
                    wait_start, resumed = time.monotonic(), True
                limit = self.stall if self.logger_tick is not None and not resumed else self.startup
                if time.monotonic() - wait_start > limit:
                    raise self._stalled("waited for the logger (STATUS last_tick %s)" % self.logger_tick, k,
                                        time.monotonic() - wait_start)
                self._handle(5)
                resend_at = self._resend_for_logger(unconfirmed, time.monotonic(), resend_at)
            sample = self._sample(k, tau, source, input_tick)
            self.awaited, self.answer = k, None
            self._send(sample)
            published = time.monotonic()
            unconfirmed[k] = sample
            for old in [t for t in unconfirmed if t <= self.logger_tick]:
                del unconfirmed[old]
            if published >= next_status:
                self.publish_status("running", k)
                next_status = published + 0.5
            deadline = published + (self.startup if k == 0 else self.stall)
            resend = published + self.retransmit
            while self.answer is None:
                if self._stop_requested():
                    self.publish_status("interrupted", k)
                    return 0
                now = time.monotonic()
                if self._take_resume():
                    deadline = max(deadline, now + self.startup)
                if now > deadline:
                    raise self._stalled("no ACTUATOR_STATE of tick %d" % k, k, now - published)
                self._handle(5)
                if self.answer is None:
                    if time.monotonic() >= resend:
                        self._send(sample, truth=False)
                        self.retransmits += 1
                        resend = time.monotonic() + self.retransmit
            if k < self.last_tick:
                tau = self._advance(k, self.answer)
                source, input_tick = TORQUE_COMMANDED, k
                self._check_limits(k + 1)
        # The end: every sample in the log first (bounded).
        deadline = time.monotonic() + self.stall
        resend_at = time.monotonic() + self.retransmit
        while (self.logger_tick is None or self.logger_tick < self.last_tick) and time.monotonic() < deadline \
                and not self._stop_requested():
            self._handle(5)
            resend_at = self._resend_for_logger(unconfirmed, time.monotonic(), resend_at)
        if self.logger_tick is None or self.logger_tick < self.last_tick:
            print("plant: warning: the logger confirmed every message up to tick %s of %d"
                  % (self.logger_tick, self.last_tick), file=sys.stderr, flush=True)
        message = "retransmits=%d log_resends=%d" % (self.retransmits, self.log_resends)
        return self._finish(message)

    def _finish(self, message, loop=None):
        if self.clipped:
            message += " torque_clipped=%d" % self.clipped
            print("plant: clipped the torque to its limits in %d periods" % self.clipped, file=sys.stderr, flush=True)
        for _ in range(3):  # the others end on it, and a datagram can be lost
            self.publish_status("finished", self.last_tick, message, loop)
        return 0

    # -- realtime --------------------------------------------------------
    def _loop_stats(self, cycles, started, lateness, misses, longest, ages, missing):
        st = loop_stats_t()
        st.period = self.period
        try:
            fifo = os.sched_getscheduler(0) == os.SCHED_FIFO
            st.scheduler = "fifo:%d" % os.sched_getparam(0).sched_priority if fifo else "other"
            cpus = os.sched_getaffinity(0)
            if len(cpus) < (os.cpu_count() or len(cpus)):
                st.scheduler += " cpus " + ",".join(str(c) for c in sorted(cpus))
        except (AttributeError, OSError):
            st.scheduler = "other"
        st.cycles = cycles
        elapsed = time.monotonic() - started
        st.achieved_rate = cycles / elapsed if elapsed > 0 else 0.0
        st.jitter_p50, st.jitter_p99, st.jitter_max = (lateness.percentile(0.5), lateness.percentile(0.99),
                                                      lateness.max)
        st.deadline_misses = misses
        st.longest_miss_run = longest
        st.input_age_p50, st.input_age_p99, st.input_age_max = (ages.percentile(0.5), ages.percentile(0.99),
                                                                ages.max)
        st.missing_inputs = missing
        st.torque_held = self.choice.held
        st.torque_zeroed = self.choice.zeroed
        st.stale_inputs = self.choice.held + self.choice.zeroed
        lat = self.latencies
        st.latency_p50, st.latency_p99, st.latency_max = lat.percentile(0.5), lat.percentile(0.99), lat.max
        return st

    def serve_realtime(self):
        self.publish_status("ready", -1)
        start = time.monotonic()
        while not all(p in self.peers for p in ("logger", "controller", "actuator")):
            if self._stop_requested():
                self.publish_status("interrupted", -1)
                return 0
            if time.monotonic() - start > self.startup:
                raise self._stalled("waited for STATUS from logger, controller and actuator", 0,
                                    time.monotonic() - start)
            self._handle(20)
        lateness, misses, miss_run, longest = _Histogram(), 0, 0, 0
        ages, used_tick = _Histogram(), -1  # how old each torque was when first applied [s]
        missing, sent = 0, 0  # periods without a new torque; ticks published
        # Deadlines on whole periods of CLOCK_MONOTONIC, as the built-in loops'
        # (transport/rate_loop.cpp): the actuator wakes half a period after
        # each, when the controller has answered, and takes only a fresh command.
        period_ns = int(round(1e9 / self.rate))
        t0_ns = (time.monotonic_ns() // period_ns + 1) * period_ns
        t0 = t0_ns * 1e-9
        next_status = t0 + 0.5
        tau, source, input_tick = [0.0] * self.joints, TORQUE_ZERO, -1
        for k in range(self.last_tick + 1):
            if self._stop_requested():
                break
            deadline = (t0_ns + k * period_ns) * 1e-9
            now = time.monotonic()
            if now > deadline:
                misses, miss_run = misses + 1, miss_run + 1
                longest = max(longest, miss_run)
            else:
                miss_run = 0
                time.sleep(deadline - now)
            woke = time.perf_counter()
            lateness.add(max(0.0, time.monotonic() - deadline))
            self._send(self._sample(k, tau, source, input_tick))
            sent += 1
            if k == self.last_tick:
                break
            self._drain(until=deadline + self.period)
            newest_tick, newest_tau = self.newest if self.newest is not None else (None, None)
            if newest_tick is None or newest_tick <= used_tick:
                missing += 1
            chosen, source, input_tick, tripped = self.choice.choose(k, newest_tick, newest_tau, self.joints)
            if tripped:
                newest = "no torque yet" if newest_tick is None else "the newest torque (tick %d)" % newest_tick
                print("plant: watchdog: %s is more than %d periods old at tick %d (t = %.6g s); commanding zero "
                      "torque%s" % (newest, self.choice.watchdog, k, k * self.period,
                                    " and braking" if self.brake else ""), file=sys.stderr, flush=True)
                if self.brake is not None:
                    self.brake()
            if source == TORQUE_COMMANDED and input_tick > used_tick:
                used_tick = input_tick
                ages.add(max(0.0, (self.headers.utime() - self.newest_utime) * 1e-6))
            tau = self._advance(k, chosen)
            self._check_limits(k + 1)
            if time.monotonic() >= next_status:
                self.publish_status("running", k, loop=self._loop_stats(sent, t0, lateness, misses, longest, ages,
                                                                        missing))
                next_status += 0.5
            self.step_cost.add(self.step_seconds)
            self.own_cost.add(time.perf_counter() - woke - self.step_seconds)
        loop = self._loop_stats(sent, t0, lateness, misses, longest, ages, missing)
        self._say_cost()
        if self._stop_requested():
            self.publish_status("interrupted", used_tick, loop=loop)  # as the built-in plant: the torque's tick
            return 0
        c = self.choice
        if c.held + c.zeroed > 0:
            print("plant: warning: stale torque: held %d periods, zeroed %d periods" % (c.held, c.zeroed),
                  file=sys.stderr, flush=True)
        message = "torque_held=%d torque_zeroed=%d" % (c.held, c.zeroed)
        if c.watchdog_trips:
            message += " watchdog_trips=%d" % c.watchdog_trips
        return self._finish(message, loop)

    def _say_cost(self):
        """plant.log's line on what a period cost: whether a rate can be held
        is step()'s time plus this module's (bench/python_helper_cost.sh reads it)."""
        if self.own_cost.n == 0:
            return
        print("plant: per period: this helper %.3f ms (median; 99 %%: %.3f ms), step() %.3f ms (median; 99 %%: "
              "%.3f ms); the period %.3f ms" % (self.own_cost.percentile(0.5) * 1e3, self.own_cost.percentile(0.99) * 1e3,
                                               self.step_cost.percentile(0.5) * 1e3,
                                               self.step_cost.percentile(0.99) * 1e3, self.period * 1e3),
              file=sys.stderr, flush=True)

    def serve(self):
        """Runs the plant until the run's last tick (or a stop); returns the exit code."""
        self._check_limits(0)
        if self.mode == "realtime":
            return self.serve_realtime()
        return self.serve_lockstep()


def _install_signals(plant):
    def stop(signum, _frame):
        plant.stop_signal = signum

    def resume(_signum, _frame):  # the launcher restarted a peer: start-up time again
        plant.resumed = True

    signal.signal(signal.SIGTERM, stop)
    signal.signal(signal.SIGINT, stop)
    signal.signal(signal.SIGCONT, resume)


def run(step, initial=None, limits=None, watchdog_periods=None, brake=None):
    """Serves step(t, u, dt) -> (q, qdot) as the run's plant until the run
    ends, then exits the program (0). A stall, a crossed limit, an error of
    the contract or of step() is printed, published as STATUS "failed", and
    exits 1; every end but "finished" calls brake() first, when given."""
    plant = None
    try:
        plant = Plant(step, initial, limits, watchdog_periods, brake)
        _install_signals(plant)
        code = plant.serve()
        if plant.stop_signal is not None:
            plant.safe_stop()  # interrupted: the arm is left safe too
    except Exception as e:  # noqa: BLE001 -- whatever ended it, the arm is made safe and the run told why
        name = os.path.basename(sys.argv[0]) or "plant"
        if isinstance(e, (ContractError, PlantStopped, LCMError)):  # said in full; anything else is a bug to trace
            print("%s: %s" % (name, e), file=sys.stderr, flush=True)
        else:
            traceback.print_exc()
        code = 1
        if plant is not None:
            try:
                plant.safe_stop()
            finally:
                try:
                    plant.publish_status("failed", -1, ("%s" % e)[:500] or type(e).__name__)
                except LCMError:
                    pass
    sys.exit(code)
