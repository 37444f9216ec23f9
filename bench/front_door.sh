#!/usr/bin/env bash
# Keeps the README's "about N minutes" honest: times its two commands on a
# fresh clone of this checkout's HEAD and compares each with what README.md
# states. The packages are this machine's: a fresh machine adds their
# installation on top (dated in docs/performance.md), so this holds the
# build and the run to the README's figure, a lower bound of a first run. Prints both and the ratio;
# exits 1 when a command took more than 1.5 times what the README says (the
# machines vary twofold from day to day: measure again before changing it).
#   bench/front_door.sh          both commands (about 20 minutes)
#   bench/front_door.sh demo     the demo only
set -euo pipefail
cd "$(dirname "$0")/.."
readme=README.md
text=$(tr '\n' ' ' <"$readme")  # a sentence may wrap
stated_demo=$(grep -oE 'The demo takes about [0-9]+ minutes' <<<"$text" | grep -oE '[0-9]+' || true)
stated_tests=$(grep -oE 'the tests about [0-9]+' <<<"$text" | grep -oE '[0-9]+' || true)
[[ -n $stated_demo && -n $stated_tests ]] || { echo "front_door: README.md states no 'about N minutes' for the demo and the tests" >&2; exit 2; }
work=$(mktemp -d)
status=0
trap '[[ $status -eq 0 ]] && rm -rf "$work"' EXIT  # a failure's logs stay
git clone -q . "$work/lagrange"
measure() {
  local name=$1 stated=$2 start=$SECONDS
  shift 2
  (cd "$work/lagrange" && "$@" >"$work/$name.log" 2>&1) || { echo "front_door: $name failed (log: $work/$name.log)" >&2; status=1; }
  local took=$((SECONDS - start))
  awk -v n="$name" -v t="$took" -v s="$stated" 'BEGIN {
    r = t / (s * 60); printf "%-6s %6.1f min measured, about %d stated: ratio %.2f%s\n", n, t / 60, s, r, (r > 1.5 ? "  (over 1.5)" : "") }'
  awk -v t="$took" -v s="$stated" 'BEGIN { exit !(t > 1.5 * s * 60) }' && status=1 || true
}
measure demo "$stated_demo" bash scripts/demo.sh --quiet
[[ ${1:-} == demo ]] || measure tests "$stated_tests" bash scripts/test.sh
exit $status
