#!/usr/bin/env bash
# `lagrange check-gains` of the shipped planar scenarios, two builds side by
# side (issue #55; docs/performance.md "check-gains"): for each round and
# each scenario, the first build's command then the second's, so that both
# meet the same load. Prints each scenario's median wall time per build and
# their ratio, the median CPU time (user + system, the children's included)
# of each, and says whether the two printed the same (the evidence line's
# own wall time aside). Exit 1 when they printed differently.
#   bench/check_gains_side_by_side.sh BEFORE_BIN AFTER_BIN [ROUNDS] [CONFIG...]
#   bench/check_gains_side_by_side.sh /tmp/old/lagrange build/bin/lagrange 5
# ROUNDS defaults to 5; the scenarios to every configs/*.yaml without a URDF arm.
set -euo pipefail
cd "$(dirname "$0")/.."
[[ $# -ge 2 ]] || { sed -n '2,10p' "$0" >&2; exit 2; }
before=$1 after=$2 rounds=${3:-5}
shift $(($# < 3 ? $# : 3))
configs=("$@")
[[ ${#configs[@]} -gt 0 ]] || mapfile -t configs < <(grep -L '^ *urdf:' configs/*.yaml)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# "wall cpu" of one command [s]; its output into $1.
timed() {
  local out=$1
  shift
  # exit 1 is a verdict (a condition violated), not a failure here
  /usr/bin/time -f '%e %U %S' -o "$work/time" "$@" >"$out" 2>&1 || true
  awk '{ print $1, $2 + $3 }' "$work/time"
}
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int(NR / 2) + 1] }'; }
status=0
printf '%-30s %10s %10s %7s %10s %10s  %s\n' scenario before after ratio "cpu before" "cpu after" output
for config in "${configs[@]}"; do
  name=$(basename "$config" .yaml)
  : >"$work/$name.before" && : >"$work/$name.after"
  for ((r = 0; r < rounds; ++r)); do
    timed "$work/out.before" "$before" check-gains "$config" >>"$work/$name.before"
    timed "$work/out.after" "$after" check-gains "$config" >>"$work/$name.after"
  done
  same=same
  # The evidence line ends with what the simulations took ("; 6.2 s; see"): not a verdict.
  cmp -s <(sed -E 's/; [0-9.]+ s; see/; T s; see/' "$work/out.before") \
    <(sed -E 's/; [0-9.]+ s; see/; T s; see/' "$work/out.after") || { same=DIFFERENT; status=1; }
  b=$(cut -d' ' -f1 "$work/$name.before" | median) a=$(cut -d' ' -f1 "$work/$name.after" | median)
  cb=$(cut -d' ' -f2 "$work/$name.before" | median) ca=$(cut -d' ' -f2 "$work/$name.after" | median)
  printf '%-30s %9.2fs %9.2fs %7.2f %9.2fs %9.2fs  %s\n' "$name" "$b" "$a" "$(echo "$a / $b" | bc -l)" "$cb" "$ca" \
    "$same"
done
echo "($rounds rounds alternating, medians; $(nproc) cores; load average $(cut -d' ' -f1-3 /proc/loadavg))"
exit $status
