#!/usr/bin/env bash
# Sets up, builds and runs the default scenario (configs/rigid_2dof.yaml),
# then prints the result and where the outputs are, plots included
# (runs/rigid_2dof/report/*.png). Arguments are passed to
# `lagrange run` (e.g. --set controller.kp=[100,8]).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
out=runs/rigid_2dof
exec build/bin/lagrange run configs/rigid_2dof.yaml --out "$out" --report "$@"
