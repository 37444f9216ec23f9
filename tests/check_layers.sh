#!/bin/bash
# Fails when an #include points up the layers (docs/architecture.md, "Layers").
# Every C++ file of the repository has a layer (below, `layer_of`; a file no
# rule places is itself an error), and each layer may include only the layers
# `allowed` lists for it, besides its own. Project includes are the quoted
# ones ("model/bounds.hpp"); "lagrange/*.hpp" are the generated message types.
# Usage: tests/check_layers.sh SOURCE_DIR     check; exit 1 on any offence
#        tests/check_layers.sh --rules        print the layers and what each
#                                             may include (docs/architecture.md
#                                             shows this table; a test compares)
set -euo pipefail

# Layer names, bottom up, with what each may include besides itself.
rules() {
  cat <<'EOF'
util       : (nothing)
model      : util
transport  : util messages
core       : util model
config     : util model core transport/fault_rule.hpp
scenario   : util model core config
lcm        : util model core config scenario transport messages
runtime    : util model config transport messages
process    : util model core config scenario lcm runtime transport messages
test       : util model core config scenario lcm runtime transport messages process
EOF
}

# The layer of a file (a path relative to the source root) or of an included
# header; empty when no rule places it.
layer_of() {
  local f=$1
  case $f in
    util/*) echo util ;;
    model/*) echo model ;;
    lagrange/*) echo messages ;;
    transport/*) echo transport ;;
    */main.cpp) echo process ;;
    */*_lcm.hpp | */*_lcm.cpp) echo lcm ;;
    controller/gain_report.* | controller/registry.* | controller/paper_controllers.* | \
      controller/gain_suggestion.* | controller/sampled_data.* | controller/baselines.*) echo scenario ;;
    controller/*) echo core ;;
    actuator/*) echo core ;;
    plant/scenario_plant.*) echo lcm ;;  # the plant a scenario describes, with its messages' translation
    plant/plant_loops.* | plant/stall_diagnosis.*) echo process ;;
    plant/*) echo core ;;
    config/*) echo config ;;
    logger/logger_loop.*) echo process ;;
    logger/*) echo lcm ;;  # metrics, summary, coverage: message-level, no process scaffolding
    runtime/*) echo runtime ;;
    tools/*) echo process ;;
    tests/* | bench/* | fuzz/*) echo test ;;
    *) echo "" ;;
  esac
}

if [[ "${1:-}" == --rules ]]; then
  rules
  exit 0
fi
cd "${1:?usage: check_layers.sh SOURCE_DIR | --rules}"

declare -A allowed
while IFS=: read -r name list; do
  name=${name// /}
  allowed[$name]=" ${list//(nothing)/} "
done < <(rules)

failures=0
checked=0
while IFS= read -r f; do
  f=${f#./}
  own=$(layer_of "$f")
  if [[ -z $own ]]; then
    echo "$f: in no layer (tests/check_layers.sh's layer_of places every C++ file)"
    failures=$((failures + 1))
    continue
  fi
  checked=$((checked + 1))
  while IFS= read -r hit; do
    line=${hit%%:*}
    header=${hit#*\"}
    header=${header%%\"*}
    [[ $header == */* ]] || continue  # a header next to the file ("rk4.hpp"): its own folder
    theirs=$(layer_of "$header")
    [[ -n $theirs ]] || continue      # not a project header (a test's "support/...")
    [[ $theirs == "$own" ]] && continue
    [[ ${allowed[$own]} == *" $theirs "* || ${allowed[$own]} == *" $header "* ]] && continue
    echo "$f:$line: #include \"$header\" <- $own may include only:${allowed[$own]}(and $own)"
    failures=$((failures + 1))
  done < <(grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$f" || true)
done < <(find . \( -name 'build*' -o -name .git -o -name runs \) -prune -o -type f \
  \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.cc' \) -print | sort)

if ((checked < 50)); then
  echo "check_layers.sh: only $checked files found under $(pwd); expected the project's sources" >&2
  exit 1
fi
if ((failures > 0)); then
  echo "$failures include(s) point up the layers or files are in none" >&2
  exit 1
fi
echo "layers: $checked files, every include points down"
