#!/usr/bin/env bash
# Re-records the golden logs of the replay tests (tests/data/golden/*.lcm).
# Run it when a change to the controller, actuator or plant outputs is
# intended; review `git diff --stat tests/data` and commit the logs with the
# change. Each log: one scenario, 1 s of simulated time, run over LCM in a
# private network namespace. tests/integration/golden_test.cpp replays them.
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
)
for entry in "${recordings[@]}"; do
  read -r name config extra <<<"$entry"
  # shellcheck disable=SC2086  # extra holds several arguments
  bash tests/in_netns.sh build/bin/lagrange run "$config" -o "$work/$name" -q --set duration=1 $extra
  # Every component must replay its own fresh recording before it is kept.
  for component in controller actuator plant; do
    build/bin/lagrange replay "$work/$name/run.lcm" --component "$component" >/dev/null
  done
  cp "$work/$name/run.lcm" "$out/$name.lcm"
  echo "recorded $out/$name.lcm ($(du -h "$out/$name.lcm" | cut -f1))"
done
