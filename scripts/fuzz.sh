#!/usr/bin/env bash
# Builds the libFuzzer target with clang (ASan + UBSan) in build-fuzz/ and
# runs it for SECONDS (default 600) on the committed corpus
# fuzz/corpus/messages, then merges what it found into the corpus (minimised).
# A finding leaves a crash-* file in build-fuzz/ and exits non-zero.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
bash scripts/setup.sh
CXX=clang++ cmake -S . -B build-fuzz -DLAGRANGE_FUZZ=ON -DLAGRANGE_BUILD_TESTS=OFF -DLAGRANGE_BUILD_JAVA=OFF \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build-fuzz -j2 --target message_fuzzer
corpus=fuzz/corpus/messages
mkdir -p "$corpus" build-fuzz/found
cd build-fuzz
./bin/message_fuzzer -max_total_time="$seconds" -max_len=4096 -print_final_stats=1 found "../$corpus"
./bin/message_fuzzer -merge=1 "../$corpus" found >/dev/null 2>&1
echo "fuzz: ${seconds} s without a finding; corpus: $(ls "../$corpus" | wc -l) inputs in $corpus"
