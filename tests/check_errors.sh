#!/bin/bash
# The error policy (util/error.hpp): production code throws lagrange::BadInput,
# lagrange::RuntimeFault or a component's kind derived from them -- never a bare
# std::runtime_error, whose exit code no command could tell. (That exit codes
# come from exitCodeOf alone is held by review and ErrorKinds.*, not here.)
# Usage: tests/check_errors.sh SOURCE_DIR   (exit 1 naming each violation)
#        tests/check_errors.sh --self-test  (a throw planted in a scratch tree is named)
set -euo pipefail
if [[ ${1:-} == --self-test ]]; then
  scratch=$(mktemp -d)
  trap 'rm -rf "$scratch"' EXIT
  mkdir "$scratch/model"
  echo 'void f() { throw std::runtime_error("x"); }' >"$scratch/model/f.cpp"
  status=0
  out=$(bash "$0" "$scratch") || status=$?
  [[ $status -eq 1 ]] || { echo "FAIL: exit $status, expected 1: $out" >&2; exit 1; }
  grep -q '^model/f.cpp:1: throws std::runtime_error' <<<"$out" || { echo "FAIL: not named: $out" >&2; exit 1; }
  echo "ok: a planted throw is named: $out"
  exit 0
fi
src=$(cd "${1:?usage: check_errors.sh SOURCE_DIR}" && pwd)
cd "$src"
status=0
# Tests, fuzzers, benchmarks and examples may throw what they like.
files=$(find . \( -name 'build*' -o -name .git -o -name tests -o -name fuzz -o -name bench -o -name examples \
  -o -name runs \) -prune -o -type f \( -name '*.cpp' -o -name '*.hpp' \) -print | sort)
for f in $files; do
  while IFS=: read -r line _; do
    echo "${f#./}:$line: throws std::runtime_error; expected lagrange::BadInput, lagrange::RuntimeFault or a kind derived from them (util/error.hpp)"
    status=1
  done < <(grep -n 'throw std::runtime_error' "$f" || true)
done
[[ $status -eq 0 ]] && echo "error policy: $(wc -w <<<"$files") files, no bare std::runtime_error thrown"
exit $status
