#!/usr/bin/env bash
# Regenerates docs/evidence/: runs every sweep of sweeps/ on this machine's
# cores (lagrange sweep) and keeps each one's table and maps in
# docs/evidence/NAME/ (sweep.csv, maps/*.png). docs/evidence.md reads them.
# About 10 minutes on 2 cores. A sweep already run into the work directory
# is resumed, not run again (lagrange sweep is resumable).
#   scripts/evidence_docs.sh [WORK_DIR]   (default: build/evidence)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh >/dev/null
work=${1:-build/evidence}
for sweep in sweeps/*.yaml; do
  name=$(basename "$sweep" .yaml)
  echo "== $name"
  build/bin/lagrange sweep "$sweep" -o "$work/$name"
  rm -rf "docs/evidence/$name"
  mkdir -p "docs/evidence/$name/maps"
  cp "$work/$name/sweep.csv" "docs/evidence/$name/"
  cp "$work/$name"/maps/*.png "docs/evidence/$name/maps/"
done
