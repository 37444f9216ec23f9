#!/usr/bin/env bash
# `lagrange tune` at -j 1 and at -j N side by side (issue #55; docs/performance.md
# "lagrange tune"): for each round the -j 1 tune then the -j N one, so that
# both meet the same load. Prints each round's wall times, the medians and
# their ratio, the runs made ahead and used at -j N (tune.json's result.runs),
# and says whether the two wrote the same evaluations (tune.jsonl without its
# times). Exit 1 when they differ.
#   bench/tune_jobs_side_by_side.sh [LAGRANGE_BIN] [ROUNDS] [JOBS] [-- TUNE_ARGS...]
#   bench/tune_jobs_side_by_side.sh build/bin/lagrange 3 2 -- configs/rigid_2dof.yaml
# LAGRANGE_BIN defaults to build/bin/lagrange, ROUNDS to 3, JOBS to the cores;
# TUNE_ARGS to the tests' short 2-joint runs (configs/rigid_2dof.yaml
# --set duration=2 --set plant.physics_step=1e-4 --set metrics.convergence_deadline=1.5).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/bin/lagrange} rounds=${2:-3} jobs=${3:-$(nproc)}
shift $(($# < 3 ? $# : 3))
[[ ${1:-} == -- ]] && shift
args=("$@")
[[ ${#args[@]} -gt 0 ]] || args=(configs/rigid_2dof.yaml --set duration=2 --set plant.physics_step=1e-4
  --set metrics.convergence_deadline=1.5)
[[ -x $bin ]] || { echo "tune_jobs_side_by_side.sh: $bin is not a program; expected the lagrange binary" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# One tune's wall time [s]; its folder $1.
timed() {
  local out=$1
  shift
  local start end
  start=$(date +%s.%N)
  "$bin" tune "${args[@]}" --out "$out" -q "$@" >"$work/log" 2>&1 || true  # exit 1 (none passed) still measures
  end=$(date +%s.%N)
  [[ -s $out/tune.jsonl ]] || { cat "$work/log" >&2; exit 1; }
  echo "$end - $start" | bc -l
}
# tune.jsonl without what varies from run to run (the times).
evaluations() {
  python3 -c 'import json, sys
for line in open(sys.argv[1]):
    e = json.loads(line); e.pop("wall_time", None); e.pop("times", None); print(json.dumps(e, sort_keys=True))' "$1"
}
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
status=0
printf '%5s %10s %10s  %s\n' round "-j 1 [s]" "-j $jobs [s]" "runs at -j $jobs (made, ahead, used); evaluations"
for ((r = 1; r <= rounds; ++r)); do
  one=$(timed "$work/one$r" -j 1) many=$(timed "$work/many$r" -j "$jobs")
  echo "$one" >>"$work/one" && echo "$many" >>"$work/many"
  runs=$(python3 -c 'import json, sys; r = json.load(open(sys.argv[1]))["result"]["runs"]
print(r["made"], r["ahead"], r["used"])' "$work/many$r/tune.json")
  same=same
  cmp -s <(evaluations "$work/one$r/tune.jsonl") <(evaluations "$work/many$r/tune.jsonl") || { same=DIFFERENT; status=1; }
  printf '%5d %10.2f %10.2f  %s; %s (%d lines)\n' "$r" "$one" "$many" "$runs" "$same" "$(wc -l <"$work/one$r/tune.jsonl")"
done
o=$(median <"$work/one") m=$(median <"$work/many")
printf 'median %9.2f %10.2f  ratio %.2f\n' "$o" "$m" "$(echo "$m / $o" | bc -l)"
echo "($rounds rounds alternating; $(nproc) cores; load average $(cut -d' ' -f1-3 /proc/loadavg))"
exit $status
