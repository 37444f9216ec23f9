#!/usr/bin/env bash
# Regenerates docs/comparison/ -- the tables and plots docs/comparison.md
# discusses -- from configs/compare_pelican.yaml: the six designs side by side
# under a 16-bit encoder, then swept over the encoder's counts per revolution
# (2^12 ... 2^20), the noise on the joint angles and the measurement delay;
# and from configs/compare_payload.yaml, over the mass of a payload the
# controllers do not know of (docs/evidence.md).
# In-process runs only (no LCM traffic); about a minute on 2 cores.
# Usage: scripts/compare_docs.sh [build dir, default build]
set -euo pipefail
cd "$(dirname "$0")/.."
bin="${1:-build}/bin/lagrange"
config=configs/compare_pelican.yaml
out=docs/comparison
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

run() {  # NAME, then lagrange compare's extra arguments
  local name=$1
  shift
  "$bin" compare "${scenario:-$config}" -o "$work/$name" -q "$@"
  mkdir -p "$out/$name"
  cp "$work/$name"/comparison.md "$work/$name"/comparison.csv "$work/$name"/*.png "$out/$name/"
}

run encoder   # compare.sweep: sensors.position.counts_per_revolution
run noise --sweep 'sensors.position.noise_sigma=[1.0e-6, 1.0e-5, 1.0e-4, 1.0e-3]'
run delay --sweep 'sensors.position.delay=[0, 1, 2, 4, 8]'
scenario=configs/compare_payload.yaml run payload   # compare.sweep: plant.payload.mass
echo "docs/comparison/ regenerated from $config and configs/compare_payload.yaml"
