#!/usr/bin/env bash
# Regenerates docs/tuning/ (docs/tuning.md, "The price of sampling"):
#  - rate.tsv and rate.png: the best convergence time `lagrange tune` finds
#    against the control rate (250 Hz to 4 kHz), and the shipped gains' own
#    time at each rate, for RATE_SCENARIO (default the Panda,
#    configs/panda_theorem1.yaml): the price of sampling for the paper's
#    controller;
#  - table.tsv and table.md: tuned against shipped gains at the shipped rate
#    for rigid_2dof, chain_m1, flexible_2dof, panda_theorem1, ur5_theorem1
#    (convergence time, peak |torque|, eq. (12) margin, the sampled-data verdict).
# Every tune is a fresh one with the default seed; the physics step at a rate
# r is the scenario's, or 1/r where that is shorter.
#   scripts/tuning_figure.sh [--rate-scenario FILE] [--rates "250 500 1000 2000 4000"]
#                            [--evaluations N] [--table-evaluations N] [--skip-table] [--skip-rates]
#                            [--redraw]   (rate.png and table.md again from the .tsv files, no tune)
# --evaluations: each rate's tune (default: tune's own, 200); --table-evaluations:
# each table row's (default 200). The Panda at five rates takes about 8 minutes
# on a 2-core machine (20 judged to the end, --full-runs); the 2-joint arm (--rate-scenario
# configs/rigid_2dof.yaml) a few minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
rate_scenario=configs/panda_theorem1.yaml
rates="250 500 1000 2000 4000"
evaluations=200 table_evaluations=200 do_table=true do_rates=true redraw=false
while [[ $# -gt 0 ]]; do
  case $1 in
    --rate-scenario) rate_scenario=$2; shift 2 ;;
    --rates) rates=$2; shift 2 ;;
    --evaluations) evaluations=$2; shift 2 ;;
    --table-evaluations) table_evaluations=$2; shift 2 ;;
    --skip-table) do_table=false; shift ;;
    --skip-rates) do_rates=false; shift ;;
    --redraw) redraw=true; shift ;;
    *) sed -n '2,20p' "$0" >&2; echo "tuning_figure.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
bin=build/bin/lagrange
[[ -x $bin ]] || { echo "tuning_figure.sh: $bin is missing; build it first (scripts/build.sh)" >&2; exit 1; }
command -v gnuplot >/dev/null || { echo "tuning_figure.sh: gnuplot is missing (apt install gnuplot-nox)" >&2; exit 1; }
out=docs/tuning
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

# One tune; prints "wall exit" and leaves DIR/tune.json (and the message in DIR.log).
tune() {
  local dir=$1
  shift
  local start=$SECONDS code=0
  nice "$bin" tune "$@" --out "$dir" -q >"$dir.log" 2>&1 || code=$?
  echo "$((SECONDS - start)) $code"
}
# The fields of a tune.json's side (input or best) as "time peak margin verdict"; "NaN" where none.
side() {
  python3 - "$1" "$2" <<'EOF'
import json, sys
r = json.load(open(sys.argv[1]))["result"]
s = r.get(sys.argv[2]) or {}
f = lambda v, fmt: "NaN" if v is None else fmt % v
print(f(s.get("convergence_time"), "%.4g"), f(s.get("peak_torque"), "%.4g"), f(s.get("margin"), "%.3g"),
      s.get("sampled_verdict") or "-")
EOF
}
physics_of() { awk '/physics_step:/ { print $2; exit }' "$1"; }

# rate.png from rate.tsv (its rates, its scenario's name).
draw_rate() {
  local rates_drawn
  rates_drawn=$(awk -F'\t' '/^[0-9]/ { printf "%s ", $1 }' "$out/rate.tsv" | sed 's/ $//')
  gnuplot <<EOF
set terminal pngcairo size 900,560 font ",11"
set output "$out/rate.png"
set datafile separator "\t"
set datafile missing "NaN"
set logscale x 2
set xtics ($(echo "$rates_drawn" | sed 's/\([0-9]*\)/"\1" \1/g; s/ "/, "/g'))
set xrange [$(echo "$rates_drawn" | awk '{ print $1 / 1.3 ":" $NF * 1.3 }')]
set yrange [0:*]
set grid
set key top right box opaque
set xlabel "control rate [Hz]"
set ylabel "convergence time from the initial state [s]"
set title noenhanced "$(awk 'NR == 1 { print $2 }' "$out/rate.tsv" | tr -d :): the price of sampling: the best convergence time lagrange tune found at each rate"
plot "$out/rate.tsv" using 1:(\$4) every ::1 with linespoints lw 2 pt 7 lc rgb "#1f77b4" title "tuned (lagrange tune)", \
     "$out/rate.tsv" using 1:(\$2) every ::1 with linespoints lw 2 dt 2 pt 5 lc rgb "#d62728" title "shipped gains", \
     "$out/rate.tsv" using 1:(\$10 == 1 ? 1.0 : NaN):("nothing passed:\nexit 1, what binds\nin rate.tsv") every ::1 \
       with labels font ",9" tc rgb "gray30" notitle
EOF
}

# table.md from table.tsv.
draw_table() {
  # The markdown table docs/tuning.md quotes.
  awk -F'\t' 'NR == 1 { print "<!-- " substr($0, 3) " -->"; next }
    NR == 2 { print "| scenario | convergence time shipped → tuned [s] | peak \\|torque\\| shipped → tuned [N m] | eq. (12) margin shipped → tuned | tuned: sampled-data check | evaluations | wall [s] |"
              print "| --- | --- | --- | --- | --- | --- | --- |"; next }
    { printf "| %s | %s → %s | %s → %s | %s → %s | %s | %s | %s |\n", $1, $2, $3, $4, $5, $6, $7, $8, $9, $10 }' \
    "$out/table.tsv" | sed 's/NaN/n\/a/g' >"$out/table.md"
}

if $redraw; then
  do_rates=false do_table=false
  [[ -f $out/rate.tsv ]] && draw_rate
  [[ -f $out/table.tsv ]] && draw_table
fi

if $do_rates; then
  base_step=$(physics_of "$rate_scenario")
  name=$(basename "$rate_scenario" .yaml)
  printf '# %s: lagrange tune --evaluations %s at each rate (%s)\n' "$name" "$evaluations" "$(date -u +%F)" >"$out/rate.tsv"
  printf 'rate_hz\tshipped_time_s\tshipped_verdict\tbest_time_s\tbest_peak_nm\tbest_margin\tbest_verdict\tevaluations\twall_s\texit\n' >>"$out/rate.tsv"
  for rate in $rates; do
    step=$(python3 -c "print(min(float('${base_step:-1e-4}'), 1.0 / $rate))")
    read -r wall code < <(tune "$work/rate$rate" "$rate_scenario" --set plant.publish_rate="$rate" \
      --set plant.physics_step="$step" --evaluations "$evaluations")
    if [[ ! -f $work/rate$rate/tune.json ]]; then
      echo "tuning_figure.sh: the tune at $rate Hz wrote nothing:" >&2
      cat "$work/rate$rate.log" >&2
      exit 1
    fi
    read -r st sp sm sv < <(side "$work/rate$rate/tune.json" input)
    read -r bt bp bm bv < <(side "$work/rate$rate/tune.json" best)
    n=$(wc -l <"$work/rate$rate/tune.jsonl")
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$rate" "$st" "$sv" "$bt" "$bp" "$bm" "$bv" "$n" "$wall" "$code" \
      | tee -a "$out/rate.tsv"
    [[ $code == 1 ]] && sed -n '/what binds/,$p' "$work/rate$rate.log" | sed "s/^/# $rate Hz: /" >>"$out/rate.tsv"
  done
  draw_rate
  echo "tuning_figure.sh: wrote $out/rate.tsv and $out/rate.png" >&2
fi

if $do_table; then
  printf '# tuned against shipped, lagrange tune --evaluations %s (%s)\n' "$table_evaluations" "$(date -u +%F)" >"$out/table.tsv"
  printf 'scenario\tshipped_time_s\ttuned_time_s\tshipped_peak_nm\ttuned_peak_nm\tshipped_margin\ttuned_margin\ttuned_verdict\tevaluations\twall_s\texit\n' >>"$out/table.tsv"
  for name in rigid_2dof chain_m1 flexible_2dof panda_theorem1 ur5_theorem1; do
    read -r wall code < <(tune "$work/$name" "configs/$name.yaml" --evaluations "$table_evaluations")
    [[ -f $work/$name/tune.json ]] || { echo "tuning_figure.sh: $name's tune wrote nothing:" >&2; cat "$work/$name.log" >&2; exit 1; }
    read -r st sp sm sv < <(side "$work/$name/tune.json" input)
    read -r bt bp bm bv < <(side "$work/$name/tune.json" best)
    n=$(wc -l <"$work/$name/tune.jsonl")
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$st" "$bt" "$sp" "$bp" "$sm" "$bm" "$bv" "$n" "$wall" "$code" \
      | tee -a "$out/table.tsv"
  done
  draw_table
  echo "tuning_figure.sh: wrote $out/table.tsv and $out/table.md" >&2
fi
