#!/usr/bin/env bash
# Installs what is missing (scripts/setup.sh), then configures and builds
# everything into build/ (binaries in build/bin/). Extra arguments go to
# cmake's configure step (e.g. -DLAGRANGE_BUILD_BENCH=OFF).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DLAGRANGE_BUILD_TESTS=ON -DLAGRANGE_BUILD_JAVA=ON \
  -DLAGRANGE_BUILD_BENCH=ON "$@" >/dev/null
cmake --build build -j2
