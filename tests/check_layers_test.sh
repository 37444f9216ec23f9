#!/bin/bash
# Proves that tests/check_layers.sh can fail: on a copy of the sources, an
# include planted up the layers (a model file including a tool, the logger's
# loop including the front end), a file in no layer, a transport header in
# config other than the fault rule, a CMake link up the layers, a library in
# two layers, an include directory other than the repository root and a bare
# include of a header from another folder are each named and fail the check;
# the copy as it is passes.
# Then docs/architecture.md must show the rules the check enforces (its
# --rules table, verbatim).
# Usage: tests/check_layers_test.sh SOURCE_DIR
set -euo pipefail
src=$(cd "${1:?usage: check_layers_test.sh SOURCE_DIR}" && pwd)
check="$src/tests/check_layers.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

mkdir "$work/tree"
(cd "$src" && find . \( -name 'build*' -o -name .git -o -name runs \) -prune -o -type f \
  \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name CMakeLists.txt \) -print0 |
  xargs -0 cp --parents -t "$work/tree")

# expect_failure NAME PATTERN: the check fails and its output matches PATTERN.
expect_failure() {
  local out status=0
  out=$(bash "$check" "$work/tree" 2>&1) || status=$?
  [[ $status -eq 1 ]] || fail "$1: exit $status, expected 1; output: $out"
  grep -qE "$2" <<<"$out" || fail "$1: output does not match '$2': $out"
  echo "ok: $1"
}

bash "$check" "$work/tree" >/dev/null || fail "the unchanged copy does not pass"

cp "$work/tree/model/bounds.cpp" "$work/bounds.cpp"
echo '#include "tools/run/run_command.hpp"' >>"$work/tree/model/bounds.cpp"
expect_failure "model including a tool" 'model/bounds\.cpp:[0-9]+: #include "tools/run/run_command\.hpp" <- model may include only: +util'
cp "$work/bounds.cpp" "$work/tree/model/bounds.cpp"

# The front end (tools/) is a layer above the processes: a process's loop
# that reached into it would run the front end inside a process.
cp "$work/tree/logger/logger_loop.cpp" "$work/logger_loop.cpp"
echo '#include "tools/run/run_command.hpp"' >>"$work/tree/logger/logger_loop.cpp"
expect_failure "a process including the front end" 'logger/logger_loop\.cpp:[0-9]+: #include "tools/run/run_command\.hpp" <- process may include only:'
cp "$work/logger_loop.cpp" "$work/tree/logger/logger_loop.cpp"

mkdir -p "$work/tree/newpart"
echo 'int f() { return 0; }' >"$work/tree/newpart/f.cpp"
expect_failure "a file in no layer" 'newpart/f\.cpp: in no layer'
rm -r "$work/tree/newpart"

cp "$work/tree/config/scenario.cpp" "$work/scenario.cpp"
echo '#include "transport/fault_rule.hpp"' >>"$work/tree/config/scenario.cpp"
bash "$check" "$work/tree" >/dev/null || fail "config including transport/fault_rule.hpp is refused"
echo '#include "transport/lcm_node.hpp"' >>"$work/tree/config/scenario.cpp"
expect_failure "config including LCM" 'config/scenario\.cpp:[0-9]+: #include "transport/lcm_node\.hpp" <- config'
cp "$work/scenario.cpp" "$work/tree/config/scenario.cpp"

# The link graph: a library linking one above its layer, and one whose
# sources sit in two layers.
cp "$work/tree/model/CMakeLists.txt" "$work/model.cmake"
echo 'target_link_libraries(lagrange_model PUBLIC lagrange::runtime)' >>"$work/tree/model/CMakeLists.txt"
expect_failure "model linking runtime" 'model/CMakeLists\.txt: lagrange_model links lagrange_runtime \(runtime\) <- model may link only: +util'
cp "$work/model.cmake" "$work/tree/model/CMakeLists.txt"
cp "$work/tree/transport/CMakeLists.txt" "$work/transport.cmake"
echo 'add_library(lagrange_mixed lcm_node.cpp ${PROJECT_SOURCE_DIR}/tools/front_end.cpp)' >>"$work/tree/transport/CMakeLists.txt"
expect_failure "a library in two layers" 'transport/CMakeLists\.txt: library lagrange_mixed mixes layers \(transport frontend\)'
cp "$work/transport.cmake" "$work/tree/transport/CMakeLists.txt"

# Include directories: one that would let a file include a header of
# another folder by its bare name, and such an include.
echo 'target_include_directories(lagrange_model PUBLIC ${PROJECT_SOURCE_DIR}/controller)' >>"$work/tree/model/CMakeLists.txt"
expect_failure "an include directory below the root" 'model/CMakeLists\.txt: lagrange_model adds the include directory \$\{PROJECT_SOURCE_DIR\}/controller'
cp "$work/model.cmake" "$work/tree/model/CMakeLists.txt"
echo 'include_directories(${PROJECT_SOURCE_DIR}/model)' >>"$work/tree/transport/CMakeLists.txt"
expect_failure "a directory-wide include directory" 'transport/CMakeLists\.txt: include_directories adds the include directory \$\{PROJECT_SOURCE_DIR\}/model'
cp "$work/transport.cmake" "$work/tree/transport/CMakeLists.txt"
echo '#include "theorem1.hpp"' >>"$work/tree/model/bounds.cpp"
expect_failure "a bare include from another folder" 'model/bounds\.cpp:[0-9]+: #include "theorem1\.hpp" is not next to model/bounds\.cpp'
cp "$work/bounds.cpp" "$work/tree/model/bounds.cpp"

bash "$check" "$work/tree" >/dev/null || fail "the restored copy does not pass"

# The picture in the docs is the one enforced.
rules=$(bash "$check" --rules)
doc="$src/docs/architecture.md"
while IFS= read -r line; do
  grep -qxF "    $line" "$doc" || fail "docs/architecture.md lacks the rule line '    $line' (print them with tests/check_layers.sh --rules)"
done <<<"$rules"
echo "ok: docs/architecture.md shows the $(wc -l <<<"$rules") rules"
