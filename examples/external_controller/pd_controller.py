#!/usr/bin/env python3
"""A PD controller from outside the project, in Python: the law of
PdController.java, with the contract kept by lagrange.external (python/).

    u = -Kp (q - q_d) - Kd v,   v = (q_k - q_{k-1}) / (t_k - t_{k-1}) (0 at the first sample),

with a constant q_d: no model, no gravity compensation -- for an arm without
gravity (robot.gravity: 0) it regulates to q_d. Without --qd, q_d is the
scenario's reference offset (reference.offset), read from the resolved scenario
the run hands over (lagrange.external.scenario()). In a scenario:

    controller:
      type: external
      command: [python3, examples/external_controller/pd_controller.py,
                --kp, "20,5", --kd, "4,1", --qd, "0.5,-0.2"]

with python/ on PYTHONPATH (or the package installed: pip install ./python).
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import lagrange.external  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    for name in ("--kp", "--kd"):
        parser.add_argument(name, required=True, help="one number, or one per joint, comma-separated")
    parser.add_argument("--qd", help="one number, or one per joint, comma-separated (default: the scenario's "
                        "reference.offset)")
    args = parser.parse_args()
    joints = int(os.environ.get("LAGRANGE_JOINTS", "0"))

    def vector(text):
        parts = [float(x) for x in text.split(",")]
        return [parts[0] if len(parts) == 1 else parts[j] for j in range(joints)]

    kp, kd = vector(args.kp), vector(args.kd)
    if args.qd is not None:
        qd = vector(args.qd)
    else:
        qd = [float(x) for x in lagrange.external.scenario()["reference"]["offset"]]
    previous = {}

    def reset():
        previous.clear()

    def step(t, q):
        if previous:
            v = [(q[j] - previous["q"][j]) / (t - previous["t"]) for j in range(joints)]
        else:
            v = [0.0] * joints
        previous["q"], previous["t"] = q, t
        error = [q[j] - qd[j] for j in range(joints)]
        u = [-kp[j] * error[j] - kd[j] * v[j] for j in range(joints)]
        return {"u": u, "q_desired": qd, "q_error": error, "theta": v}

    lagrange.external.run(step, reset)


if __name__ == "__main__":
    main()
