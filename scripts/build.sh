#!/usr/bin/env bash
# Installs what is missing (scripts/setup.sh), then configures and builds
# everything into build/ (binaries in build/bin/). Extra arguments go to
# cmake's configure step (e.g. -DLAGRANGE_BUILD_BENCH=OFF).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/configure.sh -DLAGRANGE_BUILD_TESTS=ON -DLAGRANGE_BUILD_JAVA=ON -DLAGRANGE_BUILD_BENCH=ON "$@"
cmake --build build -j2
