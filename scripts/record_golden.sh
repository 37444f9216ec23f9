#!/usr/bin/env bash
# Re-records the golden logs of the replay tests (tests/data/golden/*.lcm).
# Run it when a change to the controller, actuator or plant outputs is
# intended; review `git diff --stat tests/data` and commit the logs with the
# change. Each log: one scenario, 1 s of simulated time, run over LCM in a
# private network namespace. tests/integration/golden_test.cpp replays them.
# Usage: record_golden.sh [NAME...] -- only the named recordings (a new one
# joins without re-recording the others); all of them without arguments.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh >/dev/null
out=tests/data/golden
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

# name, config, extra arguments
recordings=(
  "rigid_2dof_lockstep configs/rigid_2dof.yaml --mode lockstep"
  "chain_m2_lockstep configs/chain_m2.yaml --mode lockstep"
  "flexible_2dof_filtered_rate_lockstep configs/flexible_2dof_filtered_rate.yaml --mode lockstep"
  "chain_m1_realtime configs/chain_m1.yaml --mode realtime"
  # recorded on ODE at 0.1 ms, as before the config moved to MuJoCo (issue #45)
  "panda_theorem1_lockstep configs/panda_theorem1.yaml --mode lockstep --set plant.engine=ode --set plant.physics_step=1e-4"
)
# How many outputs `lagrange replay LOG --component C` reproduced; empty if it did not replay exactly.
reproduced() {
  build/bin/lagrange replay "$1" --component "$2" 2>&1 | sed -n 's/.*reproduced all \([0-9]*\) recorded.*/\1/p' || true
}

for entry in "${recordings[@]}"; do
  read -r name config extra <<<"$entry"
  if (($# > 0)) && [[ " $* " != *" $name "* ]]; then continue; fi
  # A realtime run may end before the controller or actuator answered the last
  # sample or two; golden_test.cpp wants at least 1000 of the 1001 answers, so
  # such a recording is made again (a few attempts).
  for attempt in 1 2 3 4 5; do
    rm -rf "${work:?}/$name"
    # shellcheck disable=SC2086  # extra holds several arguments
    bash tests/in_netns.sh build/bin/lagrange run "$config" -o "$work/$name" -q --set duration=1 $extra
    # Every component must replay its own fresh recording before it is kept.
    complete=1
    for component in controller actuator plant; do
      n=$(reproduced "$work/$name/run.lcm" "$component")
      if [[ -z "$n" ]]; then
        echo "record_golden: $component does not replay $name exactly" >&2
        exit 1
      fi
      ((n >= 1000)) || complete=0
    done
    ((complete)) && break
    echo "record_golden: $name answered fewer than 1000 ticks (attempt $attempt), recording again" >&2
  done
  ((complete)) || { echo "record_golden: $name stayed short of 1000 answers" >&2; exit 1; }
  cp "$work/$name/run.lcm" "$out/$name.lcm"
  echo "recorded $out/$name.lcm ($(du -h "$out/$name.lcm" | cut -f1))"
done
