#!/usr/bin/env bash
# Accuracy per CPU second of the two physics engines (docs/engines_and_arms.md, "Two
# engines: accuracy per CPU second"): the Panda (configs/panda_theorem1.yaml) and a
# 7-link planar chain (bench/rigid_7link.yaml), both under the Theorem 1 controller
# at 1 kHz, on ODE and on MuJoCo (RK4) at physics steps from 1 ms to 10 us, against
# RK4 of the model at 1 us. Each run is 4 s (both converge at about 2.56 s).
# Writes docs/engine_accuracy/: the rows (panda.tsv, chain7.tsv), the tables
# (engine_accuracy.md) and the figure (engine_accuracy.png). In process, no LCM;
# the two arms run side by side, one per core: 3.4 minutes on the 2 cores of
# docs/performance.md's machine while other work kept them busy (2026-11-28).
# Usage: bench/engine_accuracy.sh [more lagrange-bench-engines options, e.g. --repeats 1]
#        bench/engine_accuracy.sh --redraw   # the tables and the figure again from the rows in docs/
set -euo pipefail
cd "$(dirname "$0")/.."
redraw=false
if [[ "${1:-}" == --redraw ]]; then
  redraw=true
  shift
fi
command -v gnuplot >/dev/null || { echo "engine_accuracy.sh: gnuplot is missing (apt install gnuplot-nox)" >&2; exit 1; }
bin=build/bin/lagrange-bench-engines
out=docs/engine_accuracy
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

if ! $redraw; then
  bash scripts/configure.sh -DLAGRANGE_BUILD_BENCH=ON
  cmake --build build -j2 --target lagrange-bench-engines >/dev/null
  start=$SECONDS
  "$bin" configs/panda_theorem1.yaml --label panda --duration 4 --out "$work/panda.tsv" "$@" >/dev/null &
  panda=$!
  "$bin" bench/rigid_7link.yaml --label chain7 --duration 4 --out "$work/chain7.tsv" "$@" >/dev/null &
  chain=$!
  wait "$panda"
  wait "$chain"
  cp "$work/panda.tsv" "$work/chain7.tsv" "$out/"
  echo "engine_accuracy.sh: both arms in $((SECONDS - start)) s" >&2
fi

# The tables: per arm, each step on both engines; then the cheapest run of each
# engine within 0.1 % and 1.5 % of the reference's convergence time.
awk -F'\t' '
  function pct(x) { return x == "NA" ? "n/a" : sprintf("%.2g %%", 100 * x) }
  function rad(x) { return x == "NA" ? "n/a" : sprintf("%.2g", x) }
  function us(s) { return sprintf("%g", s * 1e6) }
  /^#/ { sub(/^# /, ""); notes[++nn] = $0; next }
  $1 == "arm" { next }
  {
    arm = $1; if (!(arm in seen)) { seen[arm] = 1; arms[++na] = arm }
    key = arm SUBSEP $2 SUBSEP $3
    if (!((arm SUBSEP $3) in hasstep)) { hasstep[arm SUBSEP $3] = 1; steps[arm, ++ns[arm]] = $3 }
    cpu[key] = $9; err[key] = $7; gap[key] = $8; status[key] = $4
    for (t = 1; t <= 2; ++t) {
      lim = t == 1 ? 1e-3 : 1.5e-2
      if ($4 == "converged" && $7 != "NA" && $7 + 0 <= lim && (!((arm, $2, t) in best) || $9 + 0 < best[arm, $2, t])) {
        best[arm, $2, t] = $9 + 0; beststep[arm, $2, t] = $3
      }
    }
  }
  END {
    print "<!-- written by bench/engine_accuracy.sh -->"
    for (i = 1; i <= nn; ++i) print "- " notes[i]
    for (a = 1; a <= na; ++a) {
      arm = arms[a]
      printf "\n**%s**: plant CPU s per simulated s, convergence-time error, max \\|q − q_ref\\| over the run [rad]\n\n", arm
      print "| step [µs] | ODE CPU s/s | ODE t_c error | ODE max error | MuJoCo CPU s/s | MuJoCo t_c error | MuJoCo max error |"
      print "| ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
      for (i = 1; i <= ns[arm]; ++i) {
        s = steps[arm, i]; o = arm SUBSEP "ode" SUBSEP s; m = arm SUBSEP "mujoco" SUBSEP s
        printf "| %s | %.4f | %s | %s | %.4f | %s | %s |\n", us(s), cpu[o], \
          (status[o] == "converged" ? pct(err[o]) : status[o]), rad(gap[o]), cpu[m], \
          (status[m] == "converged" ? pct(err[m]) : status[m]), rad(gap[m])
      }
    }
    print "\n**CPU to reach the reference'"'"'s convergence time** (the cheapest step within it; plant CPU s per simulated s)\n"
    print "| arm | engine | within 0.1 % | within 1.5 % |"
    print "| --- | --- | --- | --- |"
    for (a = 1; a <= na; ++a)
      for (e = 1; e <= 2; ++e) {
        eng = e == 1 ? "ode" : "mujoco"; arm = arms[a]
        for (t = 1; t <= 2; ++t)
          cell[t] = (arm, eng, t) in best ? sprintf("%.4f (%s µs)", best[arm, eng, t], us(beststep[arm, eng, t])) : "not reached"
        printf "| %s | %s | %s | %s |\n", arm, eng == "ode" ? "ODE" : "MuJoCo RK4", cell[1], cell[2]
      }
    print "\n**MuJoCo within 0.1 % at the control period'"'"'s own step (1 ms), at 5 × less CPU or more than ODE needs for 1.5 %?**\n"
    for (a = 1; a <= na; ++a) {
      arm = arms[a]; m = arm SUBSEP "mujoco" SUBSEP "0.001"
      if (!(m in cpu)) continue
      within = status[m] == "converged" && err[m] + 0 <= 1e-3
      if ((arm, "ode", 2) in best) {
        ratio = best[arm, "ode", 2] / cpu[m]
        printf "- %s: MuJoCo at 1 ms is %s off (%s 0.1 %%) at %.4f CPU s/s; ODE reaches 1.5 %% at %.4f (%s µs): %.2f × MuJoCo'"'"'s CPU. %s.\n", \
          arm, pct(err[m]), (within ? "within" : "not within"), cpu[m], best[arm, "ode", 2], us(beststep[arm, "ode", 2]), ratio, \
          (within && ratio >= 5 ? "Holds" : "Does not hold")
      } else printf "- %s: ODE does not reach 1.5 %% at any step tried.\n", arm
    }
  }' "$out/panda.tsv" "$out/chain7.tsv" >"$out/engine_accuracy.md"

# The figure: one line per engine per arm; the Panda's points labelled with the step.
for arm in panda chain7; do
  for engine in ode mujoco; do
    awk -F'\t' -v e="$engine" '$2 == e && $4 == "converged" { print $9, $7, $8, $3 * 1e6 }' "$out/$arm.tsv" \
      >"$work/${arm}_$engine.dat"
  done
done
gnuplot <<EOF
set terminal pngcairo size 1400,640 font ",11"
set output "$out/engine_accuracy.png"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set grid
set xrange [3e-3:3]
set xlabel "plant CPU seconds per simulated second"
set key top right box opaque
set multiplot layout 1,2 title "Theorem 1 at 1 kHz, physics steps 1 ms to 10 µs (labels: the Panda's, in µs), against RK4 of the model at 1 µs"
set yrange [1e-16:1e5]
set ytics 1e-16, 100, 1
set title "convergence-time error |t_c - t_{c,ref}| / t_{c,ref}"
plot "$work/panda_ode.dat" using 1:2 with linespoints lw 2 pt 7 lc rgb "#d62728" title "Panda, ODE", \
     "$work/panda_mujoco.dat" using 1:2 with linespoints lw 2 pt 7 lc rgb "#1f77b4" title "Panda, MuJoCo RK4", \
     "$work/chain7_ode.dat" using 1:2 with linespoints lw 2 dt 2 pt 5 lc rgb "#ff7f0e" title "7-link chain, ODE", \
     "$work/chain7_mujoco.dat" using 1:2 with linespoints lw 2 dt 2 pt 5 lc rgb "#2ca02c" title "7-link chain, MuJoCo RK4", \
     "$work/panda_ode.dat" using 1:2:(sprintf("%g", \$4)) with labels offset 0,1 font ",9" notitle, \
     "$work/panda_mujoco.dat" using 1:2:(sprintf("%g", \$4)) with labels offset 0,1 font ",9" notitle, \
     1e-3 with lines dt 3 lc rgb "black" title "0.1 %", 1.5e-2 with lines dt 4 lc rgb "gray40" title "1.5 %"
set yrange [1e-15:1e5]
set ytics 1e-14, 100, 1
set title "max |q - q_{ref}| over the run [rad]"
plot "$work/panda_ode.dat" using 1:3 with linespoints lw 2 pt 7 lc rgb "#d62728" title "Panda, ODE", \
     "$work/panda_mujoco.dat" using 1:3 with linespoints lw 2 pt 7 lc rgb "#1f77b4" title "Panda, MuJoCo RK4", \
     "$work/chain7_ode.dat" using 1:3 with linespoints lw 2 dt 2 pt 5 lc rgb "#ff7f0e" title "7-link chain, ODE", \
     "$work/chain7_mujoco.dat" using 1:3 with linespoints lw 2 dt 2 pt 5 lc rgb "#2ca02c" title "7-link chain, MuJoCo RK4", \
     "$work/panda_ode.dat" using 1:3:(sprintf("%g", \$4)) with labels offset 0,1 font ",9" notitle, \
     "$work/panda_mujoco.dat" using 1:3:(sprintf("%g", \$4)) with labels offset 0,1 font ",9" notitle
unset multiplot
EOF
# The curve's rows in bench/results/latest.json too, beside the other figures
# of docs/performance.md (key engine_accuracy: arm -> engine -> rows by step).
python3 - "$out" bench/results/latest.json <<'PY'
import csv, json, os, sys
out, latest = sys.argv[1], sys.argv[2]
figures = json.load(open(latest)) if os.path.exists(latest) else {}
curve = {}
for arm in ("panda", "chain7"):
    rows = [line for line in open(os.path.join(out, arm + ".tsv")) if not line.startswith("#")]
    for r in csv.DictReader(rows, delimiter="\t"):
        curve.setdefault(arm, {}).setdefault(r["engine"], []).append(
            {"step": float(r["step"]), "status": r["status"], "convergence_time_error": float(r["conv_err_rel"]),
             "max_trajectory_error": float(r["max_traj_err"]), "plant_cpu_per_s": float(r["plant_cpu_per_s"])})
figures["engine_accuracy"] = curve
with open(latest, "w") as f:
    json.dump(figures, f, indent=2, sort_keys=True)
    f.write("\n")
PY
cat "$out/engine_accuracy.md"
echo "engine_accuracy.sh: wrote $out/ (panda.tsv, chain7.tsv, engine_accuracy.md, engine_accuracy.png)" >&2
