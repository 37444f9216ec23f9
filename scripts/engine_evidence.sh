#!/usr/bin/env bash
# "Does the verdict depend on the engine?" (docs/evidence.md): runs every
# sweep of sweeps/ again on MuJoCo (plant.engine: mujoco, the same physics
# step), keeps each table as docs/evidence/NAME/sweep_mujoco.csv beside the
# ODE one scripts/evidence_docs.sh made (sweep.csv), and writes the row-by-row
# comparison of the two to docs/evidence/engines.md. About 30 minutes on 2
# cores (28 measured on a busy machine); a sweep already run into the work
# directory is resumed.
#   scripts/engine_evidence.sh [WORK_DIR]   (default: build/evidence)
set -euo pipefail
cd "$(dirname "$0")/.."
work=${1:-build/evidence}
[ -x build/bin/lagrange ] || bash scripts/build.sh >/dev/null
for sweep in sweeps/*.yaml; do
  name=$(basename "$sweep" .yaml)
  [ -f "docs/evidence/$name/sweep.csv" ] ||
    { echo "engine_evidence: docs/evidence/$name/sweep.csv missing; run scripts/evidence_docs.sh first" >&2; exit 2; }
  echo "== $name on MuJoCo"
  mkdir -p "$work"
  # The same sweep with the engine set before its axes (the file's own `set:` kept).
  python3 - "$sweep" "$work/$name-mujoco.yaml" <<'PY'
import sys, re
src, dst = sys.argv[1], sys.argv[2]
text = open(src).read()
base = src.rsplit("/", 1)[0]
# scenario: is relative to the sweep file's folder; keep it pointing at the same file.
text = re.sub(r"^scenario:\s*(\S+)", lambda m: "scenario: " + (m.group(1) if m.group(1).startswith("/") else
              __import__("os").path.abspath(base + "/" + m.group(1))), text, count=1, flags=re.M)
if re.search(r"^set:", text, flags=re.M):
    text = re.sub(r"^set:\s*\{", "set: {plant.engine: mujoco, ", text, count=1, flags=re.M)
    if "plant.engine: mujoco" not in text:
        sys.exit("engine_evidence: cannot add plant.engine to the block `set:` of " + src)
else:
    text = "set: {plant.engine: mujoco}\n" + text
open(dst, "w").write(text)
PY
  build/bin/lagrange sweep "$work/$name-mujoco.yaml" -o "$work/$name-mujoco" -q
  cp "$work/$name-mujoco/sweep.csv" "docs/evidence/$name/sweep_mujoco.csv"
done
python3 scripts/engine_agreement.py docs/evidence >docs/evidence/engines.md
echo "engine_evidence: docs/evidence/engines.md"
