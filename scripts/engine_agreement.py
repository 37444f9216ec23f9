#!/usr/bin/env python3
"""Row-by-row comparison of each sweep's table on ODE (NAME/sweep.csv) and on
MuJoCo (NAME/sweep_mujoco.csv) under DIR, as Markdown on stdout: how many rows
reach the same outcome (converged, diverged, neither) on both engines, how far
their convergence times differ, and the rows that disagree. Standard library
only. Usage: scripts/engine_agreement.py DIR"""
import csv
import os
import statistics
import sys


def outcome(row):
    if row["diverged"] == "1":
        return "diverged"
    return "converged" if row["converged"] == "1" else "did not converge"


def main(folder):
    print("| sweep | rows | same outcome | converged on both | convergence time: median, largest difference | rows that differ |")
    print("| --- | --- | --- | --- | --- | --- |")
    differing = []
    for name in sorted(os.listdir(folder)):
        ode_path = os.path.join(folder, name, "sweep.csv")
        mujoco_path = os.path.join(folder, name, "sweep_mujoco.csv")
        if not (os.path.isfile(ode_path) and os.path.isfile(mujoco_path)):
            continue
        ode = {r["index"]: r for r in csv.DictReader(open(ode_path))}
        mujoco = {r["index"]: r for r in csv.DictReader(open(mujoco_path))}
        common = sorted(set(ode) & set(mujoco), key=int)
        same = [i for i in common if outcome(ode[i]) == outcome(mujoco[i])]
        both = [i for i in common if outcome(ode[i]) == "converged" == outcome(mujoco[i])]
        gaps = [abs(float(mujoco[i]["convergence_time"]) - float(ode[i]["convergence_time"])) /
                float(ode[i]["convergence_time"]) for i in both if float(ode[i]["convergence_time"]) > 0]
        gap = "—" if not gaps else "%.2g %%, %.2g %%" % (100 * statistics.median(gaps), 100 * max(gaps))
        others = [i for i in common if i not in same]
        print("| %s | %d | %d | %d | %s | %d |" % (name, len(common), len(same), len(both), gap, len(others)))
        for i in others:
            differing.append((name, i, outcome(ode[i]), outcome(mujoco[i]), ode[i], mujoco[i]))
    if differing:
        print()
        print("Rows whose outcome differs (the parameter columns as in the sweep's table):")
        print()
        print("| sweep | row | ODE | MuJoCo | ODE error at the end [rad] | MuJoCo error at the end [rad] |")
        print("| --- | --- | --- | --- | --- | --- |")
        for name, i, a, b, ra, rb in differing[:40]:
            print("| %s | %s | %s | %s | %s | %s |" % (name, i, a, b, ra["final_error"], rb["final_error"]))
        if len(differing) > 40:
            print("\n(%d more in the tables)" % (len(differing) - 40))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: engine_agreement.py DIR")
    main(sys.argv[1])
