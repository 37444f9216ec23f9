#!/bin/bash
# Fails when an #include points up the layers (docs/architecture.md, "Layers"):
#   model -> cores (controller, actuator, plant's simulation) -> config
#   -> transport (LCM and the message types only) -> *_lcm translation
#   -> runtime -> process mains, logger, tools.
# Usage: tests/check_layers.sh SOURCE_DIR. Prints every offending line with
# the rule it breaks; exit 1 if there is one, 0 otherwise.
set -euo pipefail
cd "${1:?usage: check_layers.sh SOURCE_DIR}"

failures=0
checked=0
# check RULE FORBIDDEN_REGEX FILE...: no project include of FILE may match,
# but the header $allow (if set) may be included.
allow=""
check() {
  local rule=$1 forbidden=$2
  shift 2
  local f
  for f in "$@"; do
    [[ -f $f ]] || continue
    checked=$((checked + 1))
    while IFS= read -r hit; do
      echo "$f:$hit  <- $rule"
      failures=$((failures + 1))
    done < <(grep -nE "^#include \"(${forbidden})/" "$f" | { if [[ -n $allow ]]; then grep -vF "\"$allow\""; else cat; fi; } || true)
  done
}

shopt -s nullglob
all_but_lcm_and_main() {  # the files of a folder that are neither *_lcm.* nor a process main
  local f
  for f in "$1"/*.hpp "$1"/*.cpp; do
    [[ $f == *_lcm.* || $f == */main.cpp ]] || echo "$f"
  done
}

check "model is pure mathematics: it includes only model/" \
  "controller|actuator|plant|config|transport|runtime|logger|tools|lagrange" model/*.hpp model/*.cpp
check "transport links LCM and the message types only: no config, no core" \
  "model|controller|actuator|plant|config|runtime|logger|tools" transport/*.hpp transport/*.cpp
check "the actuator core knows no config, LCM or process" \
  "config|transport|runtime|logger|tools|lagrange|plant|controller" $(all_but_lcm_and_main actuator)
check "the plant's simulation knows no config, LCM or process" \
  "config|transport|runtime|logger|tools|lagrange|controller" plant/plant_sim.hpp plant/plant_sim.cpp
check "controllers know no LCM or process (only controller_lcm and the main do)" \
  "transport|runtime|logger|tools|lagrange|plant" $(all_but_lcm_and_main controller)
allow=transport/fault_rule.hpp  # plain data, defined once (see that header)
check "config knows no LCM or process (only scenario_lcm does)" \
  "transport|runtime|logger|tools|lagrange|plant" $(all_but_lcm_and_main config)
allow=""
check "message translation sits below the process scaffolding" \
  "runtime|logger|tools" $(ls */*_lcm.hpp */*_lcm.cpp | grep -v '^logger/')
check "the logger's message translation knows its metrics core, no process scaffolding" \
  "runtime|tools" logger/*_lcm.hpp logger/*_lcm.cpp
check "runtime is scaffolding: it includes no process, logger or tool" \
  "logger|tools|plant|controller|actuator" runtime/*.hpp runtime/*.cpp

if ((checked < 50)); then
  echo "check_layers.sh: only $checked files found under $(pwd); expected the project's sources" >&2
  exit 1
fi
if ((failures > 0)); then
  echo "$failures include(s) point up the layers" >&2
  exit 1
fi
echo "layers: $checked files, every include points down"
