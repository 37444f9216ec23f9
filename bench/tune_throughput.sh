#!/usr/bin/env bash
# `lagrange tune` on the 2-joint arm (issue #55 Performance; docs/performance.md
# "lagrange tune"): ROUNDS fresh tunes of configs/rigid_2dof.yaml at the
# default budget, each timed as a whole command. Prints per round and as
# medians: the command's wall time, evaluations per second (evaluations made
# over that wall time), and the share of the wall time spent outside the
# simulated loops -- the wall time less every evaluation's run from the
# initial state and its sampled-data check's simulations (tune.jsonl's
# times.run and times.check): loading the scenario for each candidate, the
# linearised check, eq. (12)'s k_c and k_delta, NLopt, writing the files,
# starting the program. The target is < 10 %. The share is meaningful at -j 1
# (TUNE_ARGS ... -j 1): at -j 2 the runs overlap (bench/tune_jobs_side_by_side.sh
# times -j 1 against -j N).
#   bench/tune_throughput.sh [LAGRANGE_BIN] [ROUNDS] [-- TUNE_ARGS...]
#   bench/tune_throughput.sh build/bin/lagrange 5
# LAGRANGE_BIN defaults to build/bin/lagrange, ROUNDS to 5; TUNE_ARGS
# default to "configs/rigid_2dof.yaml".
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/bin/lagrange} rounds=${2:-5}
shift $(($# < 2 ? $# : 2))
[[ ${1:-} == -- ]] && shift
args=("$@")
[[ ${#args[@]} -gt 0 ]] || args=(configs/rigid_2dof.yaml)
[[ -x $bin ]] || { echo "tune_throughput.sh: $bin is not a program; expected the lagrange binary (build it first)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf '%5s %9s %11s %8s %9s %9s %10s\n' round "wall [s]" evaluations "eval/s" "loop [s]" "check [s]" outside
for ((r = 1; r <= rounds; ++r)); do
  out="$work/round$r"
  start=$(date +%s.%N)
  "$bin" tune "${args[@]}" --out "$out" -q >"$work/log" 2>&1 || true  # exit 1 (none passed) still measures
  end=$(date +%s.%N)
  [[ -s $out/tune.jsonl ]] || { cat "$work/log" >&2; exit 1; }
  python3 - "$out/tune.jsonl" "$start" "$end" "$r" <<'EOF' | tee -a "$work/rows"
import json, sys
lines = [json.loads(l) for l in open(sys.argv[1])]
wall = float(sys.argv[3]) - float(sys.argv[2])
run = sum(l.get("times", {}).get("run", 0.0) for l in lines)
check = sum(l.get("times", {}).get("check", 0.0) for l in lines)
print("%5s %9.2f %11d %8.2f %9.2f %9.2f %9.1f%%" % (sys.argv[4], wall, len(lines), len(lines) / wall, run, check,
                                                    100.0 * (wall - run - check) / wall))
EOF
done
python3 - "$work/rows" <<'EOF'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
col = lambda i: statistics.median(float(r[i].rstrip("%")) for r in rows)
print("%5s %9.2f %11d %8.2f %9.2f %9.2f %9.1f%%" % ("median", col(1), col(2), col(3), col(4), col(5), col(6)))
EOF
