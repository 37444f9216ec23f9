#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite. The suite runs inside a
# private network namespace (tests/in_netns.sh), so its LCM traffic never
# touches this machine's interfaces. Tests run one at a time: the realtime
# tests run at wall-clock rate, and on a 2-core machine a parallel neighbour
# would be what they measure.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
exec tests/in_netns.sh ctest --test-dir build --output-on-failure "$@"
