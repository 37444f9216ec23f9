#!/usr/bin/env bash
# The test suite: installs what is missing, builds (all but the benchmarks)
# and runs every test.
#   scripts/test.sh [CTEST_ARGS...]             the suite
#   scripts/test.sh --sanitize [CTEST_ARGS...]  the suite again under
#       AddressSanitizer and UndefinedBehaviorSanitizer, in build-asan/
#       (scripts/test_sanitizers.sh; .ci/run runs both)
# Tests run in parallel (ctest -j, LAGRANGE_TEST_JOBS, default 3: most of a
# lockstep run's time is its processes waiting for each other), each
# integration test in a network namespace of its own (tests/own_netns.sh), so
# neighbours never share a multicast group or a port. The tests whose result
# depends on wall-clock speed (label `serial`, listed in tests/CMakeLists.txt:
# realtime runs, deadlines, the progress bar, the browser) run alone: a
# neighbour would be what they measure.
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ "${1:-}" == --sanitize ]]; then
  shift
  exec bash scripts/test_sanitizers.sh "$@"
fi
bash scripts/build.sh -DLAGRANGE_BUILD_BENCH=OFF
exec tests/in_netns.sh ctest --test-dir build --output-on-failure -j "${LAGRANGE_TEST_JOBS:-3}" "$@"
