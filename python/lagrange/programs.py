"""lagrange from a notebook or a script: thin wrappers over the installed
programs, standard library only.

    import lagrange
    run = lagrange.run("configs/rigid_2dof.yaml", mode="inproc", duration=2.0, controller__kp=[100, 8])
    run.summary["tracking"]["convergence_time"], run.channels["PLANT_TRUTH"]["q"][-1]

    rows = lagrange.sweep("sweeps/first_sweep.yaml", jobs=2)
    [(r["index"], r["status"], r["convergence_time"]) for r in rows]

A keyword override is a scenario key with "__" for each "." (controller__kp
is controller.kp); its value goes to --set as JSON (which is YAML), so the
program reads it as --set: a keyword giving a section another type
(controller__type="pd_plus_differenced") replaces the section whole, whatever
the keywords' order, and an unknown key is refused naming a near miss
(controller__Kd: "did you mean kd?"; docs/configuration.md); args
are more options as they are (args=["--no-netns"] where user namespaces are
refused, ["--report"], ["--check-sampled"]). A keyword that cannot be a key
(a part empty or with anything but letters, digits and "_", such as "=" in
**{"controller__kp=1,x": 3}) is refused with LagrangeError before anything
runs, as is a value that is not JSON. The program is LAGRANGE_BIN,
else `lagrange` on PATH, else the build of this checkout (build/bin/lagrange
beside python/). Interrupted (Ctrl-C, a notebook's stop), the program is
stopped as Ctrl-C stops it -- its summary and log kept -- and
KeyboardInterrupt raised again.
"""

import json
import os
import re
import shutil
import signal
import subprocess
import tempfile

from . import log, logfile

__all__ = ["LagrangeError", "program", "run", "sweep"]


class LagrangeError(RuntimeError):
    """A program could not be found, or ended with an error: the message says
    which, its exit code, and its last lines; `out` is the output directory
    (kept: a failed run's log and summary.json are there)."""

    def __init__(self, message, exit_code=None, out=None):
        super().__init__(message)
        self.exit_code = exit_code
        self.out = out
        self.rows = None  # lagrange.sweep: the rows the table holds, when it was written


def program(environ=None):
    """The `lagrange` program to run: LAGRANGE_BIN, else `lagrange` on PATH,
    else build/bin/lagrange of this checkout. Raises LagrangeError naming
    where it looked."""
    environ = os.environ if environ is None else environ
    explicit = environ.get("LAGRANGE_BIN")
    if explicit:
        if os.path.isfile(explicit) and os.access(explicit, os.X_OK):
            return explicit
        raise LagrangeError("LAGRANGE_BIN=%s is not an executable file; expected the path of the lagrange "
                            "program (build/bin/lagrange, or where cmake --install put it)" % explicit)
    found = shutil.which("lagrange", path=environ.get("PATH", os.defpath))
    if found:
        return found
    here = os.path.dirname(os.path.abspath(__file__))
    checkout = os.path.normpath(os.path.join(here, "..", "..", "build", "bin", "lagrange"))
    if os.path.isfile(checkout) and os.access(checkout, os.X_OK):
        return checkout
    raise LagrangeError("the lagrange program was not found: not in LAGRANGE_BIN, not on PATH, not at %s; "
                        "build it (scripts/build.sh), install it (cmake --install build), or set LAGRANGE_BIN "
                        "to its path" % checkout)


# A scenario key's part: letters, digits and "_" (controller, kp, PLANT_POSITION, faults.receivers.logger).
_KEY_PART = re.compile(r"[A-Za-z0-9_]+\Z")


def _key(keyword):
    """The scenario key a keyword names ("__" for each "."), or LagrangeError
    when it cannot be one: a part empty or holding anything but letters,
    digits and "_" ("=", ",", a space would change what --set says)."""
    key = keyword.replace("__", ".")
    parts = key.split(".")
    for part in parts:
        if not _KEY_PART.match(part):
            raise LagrangeError("the keyword %r is not a scenario key: %s; expected a key's parts (letters, digits "
                                "and _) joined by __ for each ., e.g. controller__kp for controller.kp"
                                % (keyword, "an empty part" if not part else "the part %r" % part))
    return key


def _sets(overrides):
    """The --set options of the keywords, and each key's keyword (for
    _call, which names the keyword where the program names --set)."""
    args, keywords = [], {}
    for keyword, value in overrides.items():
        key = _key(keyword)
        try:
            text = json.dumps(value, allow_nan=False)
        except (TypeError, ValueError) as e:
            raise LagrangeError("the value of %s (keyword %s) is not JSON: %s; expected a number, a string, a list "
                                "or a dict of them" % (key, keyword, e)) from None
        args += ["--set", "%s=%s" % (key, text)]
        keywords[key] = keyword
    return args, keywords


def _as_keywords(message, keywords):
    """The program's message with the keywords the script wrote where it
    names the --set options they became ("(from --set controller.Kd=...)"
    becomes "(from the keyword controller__Kd=...)")."""
    for key, keyword in keywords.items():
        message = message.replace("--set %s=" % key, "the keyword %s=" % keyword)
    if keywords:
        message = message.replace("keys from --set too", "keys from keywords too")
    return message


def _call(args, out, what, keywords=None):
    try:
        child = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                 errors="replace")
    except OSError as e:
        raise LagrangeError("cannot start %s: %s" % (args[0], e), out=out) from None
    try:
        stdout, stderr = child.communicate()
    except KeyboardInterrupt:
        # As Ctrl-C at a terminal: the program stops its processes, writes
        # what it has and exits 130; never a kill that would leave its key.
        child.send_signal(signal.SIGINT)
        child.communicate()
        raise
    if child.returncode != 0:
        tail = "\n".join((stderr.strip() or stdout.strip()).splitlines()[-15:])
        tail = _as_keywords(tail, keywords or {})
        raise LagrangeError("%s exited with %d:\n%s" % (what, child.returncode, tail), child.returncode, out)
    return stdout


def run(scenario, out=None, mode=None, args=(), **overrides):
    """Runs `lagrange run SCENARIO` (a scenario file's path) and returns the
    run as lagrange.log.load gives it (per-channel columns, `summary`,
    `scenario`). out: the output directory (default: a new temporary one,
    kept); mode: "lockstep", "realtime" or "inproc" (default: the
    scenario's); args: more options as they are (["--no-netns"],
    ["--report"]); **overrides: --set, with "__" for "." (a keyword that
    cannot be a scenario key is refused). Raises LagrangeError when a keyword
    or its value is refused, the program is missing or the run fails (exit
    code, last lines, `out`)."""
    if not os.path.isfile(str(scenario)):
        raise LagrangeError("the scenario %s is not a file; expected the path of a scenario YAML file" % scenario)
    sets, keywords = _sets(overrides)  # a keyword that is no key is refused before anything runs
    out = out if out is not None else tempfile.mkdtemp(prefix="lagrange-run-")
    command = [program(), "run", str(scenario), "--out", str(out), "--quiet"]
    if mode is not None:
        command += ["--mode", mode]
    _call(command + sets + [str(a) for a in args], out, "lagrange run %s" % scenario, keywords)
    try:
        return log.load(out)
    except log.LogError as e:  # the run's files are not what it wrote (replaced, or another program's)
        raise LagrangeError("lagrange run %s: %s" % (scenario, e), out=out) from e


def sweep(spec, out=None, jobs=None, args=()):
    """Runs `lagrange sweep SPEC` (a sweep file's path: it names its scenario
    and axes, docs/sweeps.md) and returns its rows (OUT/sweep.jsonl, one dict
    per run, in index order). Each axis value is typed as the scenario reads
    it: a number a float, a vector gain a list of floats (row["controller.kd"]
    == [5.0, 0.4]), true/false a bool, other text a str (docs/sweeps.md, "Axis
    values"); a norm axis is two keys, KEY.norm and KEY.direction.
    out: the output directory (default: a new
    temporary one; one that holds this sweep is resumed); jobs: runs at a
    time (default: one per core); args: more options as they are. Raises
    LagrangeError as run() does; when rows failed (exit 1), its `rows` are
    those the table holds."""
    if not os.path.isfile(str(spec)):
        raise LagrangeError("the sweep %s is not a file; expected the path of a sweep YAML file" % spec)
    if jobs is not None:
        try:
            jobs = int(jobs)
        except (TypeError, ValueError):
            raise LagrangeError("jobs=%r: expected a whole number of runs at a time" % (jobs,)) from None
    out = out if out is not None else tempfile.mkdtemp(prefix="lagrange-sweep-")
    command = [program(), "sweep", str(spec), "--out", str(out), "--quiet"]
    if jobs is not None:
        command += ["--jobs", str(jobs)]
    try:
        _call(command + [str(a) for a in args], out, "lagrange sweep %s" % spec)
    except LagrangeError as e:
        if e.exit_code == 1:  # rows failed or are missing: the table holds the others
            e.rows = _rows(out)
        raise
    return _rows(out)


# tools/sweep/sweep_files.hpp: kMaxSweepLineBytes, the longest row the C++ readers take.
MAX_ROW_BYTES = 64 << 10


def _rows(out):
    """OUT/sweep.jsonl's rows in index order ([] when there is none), read as
    the C++ readers read it: a regular file (never a FIFO), each line at most
    MAX_ROW_BYTES, JSON nested at most log.MAX_JSON_DEPTH levels."""
    path = os.path.join(str(out), "sweep.jsonl")
    if not os.path.lexists(path):
        return []
    expected = "the sweep's rows (one JSON object a line, as lagrange sweep writes them)"
    rows = []
    try:
        fd, _ = logfile.open_regular(path, expected)
        os.set_blocking(fd, True)
        with os.fdopen(fd, "rb") as f:
            for number, line in enumerate(iter(lambda: f.readline(MAX_ROW_BYTES + 1), b""), 1):
                where = "'%s' line %d" % (path, number)
                if len(line) > MAX_ROW_BYTES:
                    raise log.LogError("%s is longer than %d bytes; expected %s" % (where, MAX_ROW_BYTES, expected))
                try:
                    text = line.decode("utf-8")
                except UnicodeDecodeError:
                    raise log.LogError("%s is not UTF-8 text; expected %s" % (where, expected)) from None
                if text.strip():
                    row = log.parse_json(text, where, expected)
                    if not isinstance(row, dict):
                        raise log.LogError("%s is not a JSON object; expected %s" % (where, expected))
                    rows.append(row)
    except log.LogError as e:
        raise LagrangeError(str(e), out=out) from e
    return sorted(rows, key=lambda r: r.get("index", 0) if isinstance(r.get("index", 0), (int, float)) else 0)
