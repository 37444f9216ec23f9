"""lagrange.tune: `lagrange tune` from a notebook or a script (docs/tuning.md),
standard library only.

    best, evaluations = lagrange.tune("configs/rigid_2dof.yaml", evaluations=40, duration=3.0)
    best["convergence_time"], best["gains"]["kp"]
    [e["value"] for e in evaluations]

Keyword overrides are scenario keys as for lagrange.run ("__" for each ".",
the value as JSON); the program is found as lagrange.run finds it.
"""

import json
import os
import tempfile

from . import log
from .programs import LagrangeError, _call, _sets, program

__all__ = ["tune"]


def _number(name, value, kind):
    try:
        number = kind(value)
    except (TypeError, ValueError):
        raise LagrangeError("%s=%r: expected a positive number" % (name, value)) from None
    if not number > 0:
        raise LagrangeError("%s=%r: expected a positive number" % (name, value))
    return number


def _read_json(path, expected, out):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        raise LagrangeError("cannot read %s (%s); expected %s" % (path, e, expected), out=out) from None


def evaluations_of(out):
    """OUT/tune.jsonl's evaluations, one dict each, in the search's order (then
    the confirm phase's, `phase` "confirm": docs/tuning.md)."""
    path = os.path.join(str(out), "tune.jsonl")
    rows = []
    if not os.path.exists(path):
        return rows
    expected = "the evaluations lagrange tune writes (one JSON object a line)"
    try:
        with open(path, encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                if line.strip():
                    rows.append(log.parse_json(line, "'%s' line %d" % (path, number), expected))
    except (OSError, UnicodeDecodeError, log.LogError) as e:
        raise LagrangeError("cannot read %s: %s" % (path, e), out=out) from None
    return rows


def tune(scenario, out=None, evaluations=None, minutes=None, jobs=None, seed=None, require_condition=False,
         full_runs=False, args=(), **overrides):
    """Runs `lagrange tune SCENARIO` and returns (best, evaluations): best is
    tune.json's result.best (the gains, convergence_time, peak_torque,
    margin, sampled_verdict, ...), evaluations the lines of tune.jsonl.
    out: the output directory (default: a new temporary one; one that holds
    this tune is resumed); evaluations, minutes: the budget; jobs: the
    sampled-data check's processes; seed: the global phase's seed;
    require_condition: keep only gains for which eq. (12) holds; full_runs:
    judge every candidate's run to its end (--full-runs); args: more
    options as they are (["--span", "1"]). Raises LagrangeError when an
    argument is refused, the program is missing, or no gains passed (exit 1,
    the message naming what binds; e.out holds tune.jsonl)."""
    if not os.path.isfile(str(scenario)):
        raise LagrangeError("the scenario %s is not a file; expected the path of a scenario YAML file" % scenario)
    sets, keywords = _sets(overrides)
    command = [program(), "tune", str(scenario)]
    if evaluations is not None:
        command += ["--evaluations", str(_number("evaluations", evaluations, int))]
    if minutes is not None:
        command += ["--minutes", repr(_number("minutes", minutes, float))]
    if jobs is not None:
        command += ["--jobs", str(_number("jobs", jobs, int))]
    if seed is not None:
        command += ["--seed", str(int(seed))]
    if require_condition:
        command += ["--require-condition"]
    if full_runs:
        command += ["--full-runs"]
    out = out if out is not None else tempfile.mkdtemp(prefix="lagrange-tune-")
    command += ["--out", str(out), "--quiet"]
    _call(command + sets + [str(a) for a in args], out, "lagrange tune %s" % scenario, keywords)
    result = _read_json(os.path.join(str(out), "tune.json"), "the tune.json lagrange tune writes", out)
    # (result is null while a tune runs, and after one was killed.)
    return (result.get("result") or {}).get("best"), evaluations_of(out)
