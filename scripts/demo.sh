#!/usr/bin/env bash
# A first run: installs only what building and running a scenario needs
# (scripts/setup.sh --run), builds only the five programs of a run, runs the
# default scenario (configs/rigid_2dof.yaml) and prints the result and where
# the outputs are, plots included (runs/rigid_2dof/report/*.png). Arguments
# are passed to `lagrange run` (e.g. --set controller.kp=[100,8]).
# A build/ configured before (by scripts/build.sh or scripts/test.sh) is kept
# as it is; a new one (scripts/configure.sh: the flags scripts/build.sh uses)
# leaves out the tests, benchmarks and the Java classes, which
# scripts/build.sh adds later without rebuilding what is built.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --run
if [[ ! -f build/CMakeCache.txt ]]; then
  bash scripts/configure.sh -DLAGRANGE_BUILD_TESTS=OFF -DLAGRANGE_BUILD_BENCH=OFF -DLAGRANGE_BUILD_JAVA=OFF
fi
cmake --build build -j2 --target programs
out=runs/rigid_2dof
exec build/bin/lagrange run configs/rigid_2dof.yaml --out "$out" --report "$@"
