#!/usr/bin/env bash
# The plant helpers' own cost per period, Python (lagrange.external_plant)
# beside C++ (lagrange::sdk::runPlant): each runs the two-link example arm
# (examples/external_plant/two_link_plant.py, examples/cpp_plant/two_link_plant.cpp:
# the same RK4, four steps a period) as the plant of a realtime run at 1 kHz
# under the Theorem 1 controller, and says at its end, in plant.log, the
# median time a period took besides step() ("this helper") and step()'s own.
# Each helper runs RUNS times, alternating; the figures are the medians of
# the runs' medians. The runs are real: lagrange run, its four processes over
# LCM, in a private network namespace (tests/in_netns.sh: nothing on the
# machine's interfaces).
#
#   bench/python_helper_cost.sh [RUNS] [DURATION_S]     # default 5 runs of 3 s
#
# Needs the build's lagrange and its processes (build/bin) and its SDK
# (build/sdk/liblagrange_sdk.a): the C++ example is compiled here against
# them, as a program from outside would be (benchmarks off or on alike).
# docs/external_programs.md ("Cost per period") holds the figures measured.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
if [[ "${LAGRANGE_TEST_NETNS:-}" != 1 ]]; then
  exec "$here/tests/in_netns.sh" "$0" "$@"
fi
runs=${1:-5}
duration=${2:-3}
build=${LAGRANGE_BUILD_DIR:-$here/build}
bin=$build/bin
for needed in "$bin/lagrange" "$build/sdk/liblagrange_sdk.a"; do
  [[ -e $needed ]] || { echo "python_helper_cost.sh: $needed is not built; expected the build in $build" >&2; exit 2; }
done
work=$(mktemp -d /tmp/lagrange-helper-cost.XXXXXX)
trap 'rm -rf "$work"' EXIT
# shellcheck disable=SC2046 # pkg-config's flags are words
g++ -std=c++17 -O2 -I"$here/sdk/include" -I"$build/lcmtypes/cpp" "$here/examples/cpp_plant/two_link_plant.cpp" \
  "$build/sdk/liblagrange_sdk.a" $(pkg-config --cflags --libs lcm libcrypto) -o "$work/cpp_plant"
export PYTHONPATH="$here/python${PYTHONPATH:+:$PYTHONPATH}"

scenario() {  # $1: the plant's command as a YAML list
  sed -e "s|^duration: .*|duration: $duration|" -e "s|^mode: .*|mode: realtime|" \
      -e "s|^  command: \[python3, two_link_plant.py\].*|  command: $1|" \
      "$here/examples/external_plant/rigid_2dof_external.yaml"
}
scenario "[python3, $here/examples/external_plant/two_link_plant.py]" >"$work/python.yaml"
scenario "[$work/cpp_plant]" >"$work/cpp.yaml"
grep -q "mode: realtime" "$work/python.yaml" && grep -q "cpp_plant\]" "$work/cpp.yaml" ||
  { echo "python_helper_cost.sh: the example scenario changed; expected its mode and command lines" >&2; exit 2; }

# plant.log's "per period: this helper A ms (median; ...), step() B ms (median; ...)" -> "A B"
figures() {
  sed -n 's/.*per period: this helper \([0-9.]*\) ms (median[^)]*), step() \([0-9.]*\) ms (median.*/\1 \2/p' "$1" | tail -1
}
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

for i in $(seq 1 "$runs"); do
  for helper in python cpp; do
    out="$work/$helper-$i"
    if ! "$bin/lagrange" run "$work/$helper.yaml" --out "$out" >"$out.txt" 2>&1; then
      echo "python_helper_cost.sh: the $helper run $i failed; its output:" >&2
      tail -20 "$out.txt" >&2
      tail -20 "$out/plant.log" >&2 || true
      exit 1
    fi
    f=$(figures "$out/plant.log")
    [[ -n $f ]] || { echo "python_helper_cost.sh: no per-period line in $out/plant.log" >&2; exit 1; }
    misses=$(python3 -c "import json,sys; l=json.load(open(sys.argv[1]))['timing']['loops']['plant']; \
print(l['deadline_misses'], l['cycles'])" "$out/summary.json")
    echo "$helper $f $misses" >>"$work/figures"
    echo "run $i $helper: helper ${f% *} ms, step() ${f#* } ms, deadline misses ${misses% *} of ${misses#* }" >&2
  done
done

echo "plant helpers' cost per period, median of $runs runs of ${duration} s at 1 kHz ($(date -u +%Y-%m-%d), $(nproc) cores)"
for helper in python cpp; do
  own=$(awk -v h="$helper" '$1 == h {print $2}' "$work/figures" | median)
  step=$(awk -v h="$helper" '$1 == h {print $3}' "$work/figures" | median)
  miss=$(awk -v h="$helper" '$1 == h {print $4}' "$work/figures" | median)
  printf '  %-6s helper %.3f ms, step() %.3f ms, deadline misses %s (median)\n' "$helper" "$own" "$step" "$miss"
done
