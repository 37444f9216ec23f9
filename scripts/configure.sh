#!/usr/bin/env bash
# Configures build/ the one way every script builds it: RelWithDebInfo at
# -O2 -g1 (line tables: a quarter faster to build than -g, docs/development.md, "Building").
# The demo and scripts/build.sh share it, so that a build/ the demo made is
# not rebuilt from scratch by a later scripts/test.sh for a flag of its own.
# Extra arguments go to cmake (e.g. -DLAGRANGE_BUILD_TESTS=OFF).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" "$@" >/dev/null
