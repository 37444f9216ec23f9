#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) in build-fuzz/ and
# runs each for SECONDS (default 600) on its committed corpus -- message_fuzzer
# on fuzz/corpus/messages, log_reader_fuzzer on fuzz/corpus/logs -- then merges
# what it found into the corpus (minimised). FUZZERS="log_reader_fuzzer" runs
# only the ones named. A finding leaves a crash-* file in build-fuzz/ and exits non-zero.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
fuzzers=${FUZZERS:-"message_fuzzer log_reader_fuzzer"}
bash scripts/setup.sh
CXX=clang++ cmake -S . -B build-fuzz -DLAGRANGE_FUZZ=ON -DLAGRANGE_BUILD_TESTS=OFF -DLAGRANGE_BUILD_JAVA=OFF \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
# shellcheck disable=SC2086
cmake --build build-fuzz -j2 --target $fuzzers
for fuzzer in $fuzzers; do
  case $fuzzer in
    message_fuzzer) corpus=fuzz/corpus/messages max_len=4096 ;;
    log_reader_fuzzer) corpus=fuzz/corpus/logs max_len=8192 ;;
    *) echo "fuzz: unknown fuzzer $fuzzer; expected message_fuzzer or log_reader_fuzzer" >&2; exit 2 ;;
  esac
  mkdir -p "$corpus" "build-fuzz/found-$fuzzer"
  (cd build-fuzz && ./bin/$fuzzer -max_total_time="$seconds" -max_len=$max_len -print_final_stats=1 \
    "found-$fuzzer" "../$corpus" && ./bin/$fuzzer -merge=1 "../$corpus" "found-$fuzzer" >/dev/null 2>&1)
  echo "fuzz: $fuzzer ${seconds} s without a finding; corpus: $(ls "$corpus" | wc -l) inputs in $corpus"
done
