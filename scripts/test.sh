#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite. The suite runs inside a
# private network namespace (tests/in_netns.sh), so its LCM traffic never
# touches this machine's interfaces. Tests run one at a time: the realtime
# tests run at wall-clock rate, and on a 2-core machine a parallel neighbour
# would be what they measure. Then the suite runs again under AddressSanitizer
# and UndefinedBehaviorSanitizer (scripts/test_sanitizers.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
tests/in_netns.sh ctest --test-dir build --output-on-failure "$@"
# Then again under ASan and UBSan (build-asan/), all but the timing tests.
bash scripts/test_sanitizers.sh "$@"
