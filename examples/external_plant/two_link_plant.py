#!/usr/bin/env python3
"""A plant from outside the project, in plain Python: the two-link planar arm
of configs/rigid_2dof.yaml (the Pelican arm of Kelly, Santibanez and Loria)
integrated by classical fourth-order Runge-Kutta, with the contract kept by
lagrange.external_plant (python/).

    M(q) q'' + C(q, q') q' + g(q) = tau,

q_1 measured from the downward vertical, q_2 relative to link 1 (the
convention of plant_position_t.q); each link's mass m_i, length l_i, centre
of mass l_ci along it and inertia I_i about the centre of mass are read from
the resolved scenario (robot.links, robot.gravity), the torque held over
each period. In a scenario:

    plant:
      type: external
      command: [python3, examples/external_plant/two_link_plant.py]

Options: --substeps N (RK4 steps per period, default 4); --torque-limit,
--position-limit, --rate-limit, --watchdog-periods: the guards of a bridge
to a real arm (lagrange.external_plant.Limits; docs/hardware.md), off by
default.
"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import lagrange.external  # noqa: E402
import lagrange.external_plant  # noqa: E402


class TwoLinkArm:
    def __init__(self, links, gravity):
        if len(links) != 2:
            raise SystemExit("two_link_plant.py: the scenario's arm has %d links; expected 2" % len(links))
        (self.m1, self.l1, self.lc1, self.i1), (self.m2, _, self.lc2, self.i2) = [
            (float(k["mass"]), float(k["length"]), float(k["com"]), float(k["inertia"])) for k in links]
        self.g = float(gravity)

    def mass_matrix(self, q2):
        m2, l1, lc2 = self.m2, self.l1, self.lc2
        c2 = math.cos(q2)
        m11 = self.m1 * self.lc1 ** 2 + m2 * (l1 ** 2 + lc2 ** 2 + 2 * l1 * lc2 * c2) + self.i1 + self.i2
        m12 = m2 * (lc2 ** 2 + l1 * lc2 * c2) + self.i2
        m22 = m2 * lc2 ** 2 + self.i2
        return m11, m12, m22

    def acceleration(self, q, qd, tau):
        m11, m12, m22 = self.mass_matrix(q[1])
        h = self.m2 * self.l1 * self.lc2 * math.sin(q[1])
        coriolis = (-h * (2 * qd[0] * qd[1] + qd[1] ** 2), h * qd[0] ** 2)
        s1, s12 = math.sin(q[0]), math.sin(q[0] + q[1])
        gravity = ((self.m1 * self.lc1 + self.m2 * self.l1) * self.g * s1 + self.m2 * self.lc2 * self.g * s12,
                   self.m2 * self.lc2 * self.g * s12)
        r1 = tau[0] - coriolis[0] - gravity[0]
        r2 = tau[1] - coriolis[1] - gravity[1]
        det = m11 * m22 - m12 * m12
        return ((m22 * r1 - m12 * r2) / det, (m11 * r2 - m12 * r1) / det)

    def energy(self, q, qd):
        m11, m12, m22 = self.mass_matrix(q[1])
        kinetic = 0.5 * (m11 * qd[0] ** 2 + 2 * m12 * qd[0] * qd[1] + m22 * qd[1] ** 2)
        potential = -((self.m1 * self.lc1 + self.m2 * self.l1) * self.g * math.cos(q[0])
                      + self.m2 * self.lc2 * self.g * math.cos(q[0] + q[1]))
        return kinetic, potential

    def rk4(self, q, qd, tau, h):
        def f(x):
            a = self.acceleration(x[:2], x[2:], tau)
            return (x[2], x[3], a[0], a[1])

        x = tuple(q) + tuple(qd)
        k1 = f(x)
        k2 = f(tuple(xi + 0.5 * h * ki for xi, ki in zip(x, k1)))
        k3 = f(tuple(xi + 0.5 * h * ki for xi, ki in zip(x, k2)))
        k4 = f(tuple(xi + h * ki for xi, ki in zip(x, k3)))
        x = tuple(xi + h / 6.0 * (a + 2 * b + 2 * c + d) for xi, a, b, c, d in zip(x, k1, k2, k3, k4))
        return list(x[:2]), list(x[2:])


def numbers(text):
    return [float(x) for x in text.split(",")]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--substeps", type=int, default=4, help="RK4 steps per period (default 4)")
    parser.add_argument("--torque-limit", type=numbers, help="|u_i| limits [N m], comma-separated")
    parser.add_argument("--position-limit", type=numbers,
                        help="lower,upper per joint [rad], comma-separated: lo1,hi1,lo2,hi2")
    parser.add_argument("--rate-limit", type=numbers, help="|qdot_i| limits [rad/s], comma-separated")
    parser.add_argument("--watchdog-periods", type=int, help="zero torque when the newest is older than this")
    args = parser.parse_args()
    if args.substeps < 1:
        parser.error("--substeps must be >= 1")

    try:
        scenario = lagrange.external.scenario()
    except lagrange.external.ContractError as e:
        sys.exit("two_link_plant.py: %s" % e)
    arm = TwoLinkArm(scenario["robot"]["links"], scenario["robot"]["gravity"])
    state = {"q": [float(x) for x in scenario["initial_state"]["q"]],
             "qdot": [float(x) for x in scenario["initial_state"]["qdot"]]}

    def step(t, u, dt):
        h = dt / args.substeps
        for _ in range(args.substeps):
            state["q"], state["qdot"] = arm.rk4(state["q"], state["qdot"], u, h)
        kinetic, potential = arm.energy(state["q"], state["qdot"])
        return {"q": state["q"], "qdot": state["qdot"], "kinetic_energy": kinetic, "potential_energy": potential}

    def initial():
        kinetic, potential = arm.energy(state["q"], state["qdot"])
        return {"q": state["q"], "qdot": state["qdot"], "kinetic_energy": kinetic, "potential_energy": potential}

    limits = None
    if args.torque_limit or args.position_limit or args.rate_limit:
        position = None
        if args.position_limit:
            position = list(zip(args.position_limit[0::2], args.position_limit[1::2]))
        limits = lagrange.external_plant.Limits(args.torque_limit, position, args.rate_limit)
    lagrange.external_plant.run(step, initial=initial, limits=limits, watchdog_periods=args.watchdog_periods)


if __name__ == "__main__":
    main()
