#!/usr/bin/env bash
# Runs every benchmark (docs/performance.md), prints the table with targets,
# writes bench/results/latest.json and compares with bench/baseline.json.
# Everything runs inside a private network namespace. About 4 minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p bench/results
exec tests/in_netns.sh build/bin/lagrange-bench --bin build/bin --configs configs \
  --out bench/results/latest.json --baseline bench/baseline.json "$@"
