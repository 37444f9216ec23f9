#!/usr/bin/env bash
# Runs one test in a network namespace of its own (tests/in_netns.sh), also
# when the suite as a whole already runs in one: ctest runs integration tests
# side by side, and each must have its multicast groups, ports and leftover
# processes to itself. CMake's CROSSCOMPILING_EMULATOR of integration_tests.
LAGRANGE_TEST_NETNS= exec "$(dirname "$0")/in_netns.sh" "$@"
