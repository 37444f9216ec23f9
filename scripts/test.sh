#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite. The suite runs inside a
# private network namespace (tests/in_netns.sh), so its LCM traffic never
# touches this machine's interfaces.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
exec tests/in_netns.sh ctest --test-dir build --output-on-failure -j2 "$@"
