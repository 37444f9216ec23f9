#!/bin/bash
# Fails when an #include points up the layers (docs/architecture.md, "Layers").
# Every C++ file of the repository has a layer (below, `place`; a file no
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
config     : util model transport/fault_rule.hpp
scenario   : util model core config
lcm        : util model core config scenario transport messages
runtime    : util model config transport messages
logs       : util model config transport messages
wiring     : util model core config scenario lcm runtime transport messages
process    : util model core config scenario lcm runtime transport messages logs wiring
frontend   : util model core config scenario lcm runtime transport messages logs wiring process
test       : util model core config scenario lcm runtime transport messages logs wiring process frontend sdk
sdk        : messages transport/checksum.hpp
example    : messages sdk
EOF
}

# The layer of a file (a path relative to the source root) or of an included
# header, in $layer; empty when no rule places it. (A variable, not output:
# the check asks this for every include, and a subshell per question made it
# take seconds.)
place() {
  local f=$1
  layer=""
  case $f in
    util/*) layer=util ;;
    model/*) layer=model ;;
    sdk/* | lagrange/sdk/*) layer=sdk ;;  # the installed C++ SDK: messages only, built out of tree
    examples/*) layer=example ;;
    lagrange/*) layer=messages ;;
    transport/*) layer=transport ;;
    */main.cpp) layer=process ;;
    */*_lcm.hpp | */*_lcm.cpp) layer=lcm ;;
    controller/gain_report.* | controller/gain_report_json.* | controller/registry.* | controller/paper_controllers.* | controller/paper_section.* | \
      controller/gain_suggestion.* | controller/sampled_data.* | controller/baselines.*) layer=scenario ;;
    controller/controller_loop.*) layer=process ;;  # the controller process's loop, as plant_loops
    controller/*) layer=core ;;
    actuator/*) layer=core ;;
    plant/scenario_plant.* | plant/sensor_models.* | plant/robot_kinds.*) layer=lcm ;;  # the plant a scenario describes, with its messages' translation
    plant/plant_loops.* | plant/stall_diagnosis.*) layer=process ;;
    plant/*) layer=core ;;
    config/*) layer=config ;;
    logger/logger_loop.*) layer=process ;;
    logger/*) layer=lcm ;;  # metrics, summary, coverage: message-level, no process scaffolding
    runtime/*) layer=runtime ;;
    logs/*) layer=logs ;;
    wiring/*) layer=wiring ;;
    tools/*) layer=frontend ;;  # the lagrange front end: starts the processes, never started by them
    tests/* | bench/* | fuzz/*) layer=test ;;
    *) layer="" ;;
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
mapfile -t files < <(find . \( -name 'build*' -o -name .git -o -name runs \) -prune -o -type f \
  \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.cc' \) -print | sed 's|^\./||' | sort)
declare -A own_layer
for f in "${files[@]}"; do
  place "$f"
  if [[ -z $layer ]]; then
    echo "$f: in no layer (tests/check_layers.sh's place() puts every C++ file in one)"
    failures=$((failures + 1))
    continue
  fi
  own_layer[$f]=$layer
  checked=$((checked + 1))
done
# Every quoted include of every file, in one grep: "FILE:LINE:#include "H"".
while IFS= read -r hit; do
  f=${hit%%:*}
  rest=${hit#*:}
  line=${rest%%:*}
  own=${own_layer[$f]:-}
  [[ -n $own ]] || continue  # in no layer: said above
  header=${rest#*\"}
  header=${header%%\"*}
  if [[ $header != */* ]]; then
    # A header next to the file ("rk4.hpp"): its own folder, so its own layer
    # -- if it is there; found anywhere else it came through an include
    # directory this check does not know.
    [[ -f $(dirname "$f")/$header ]] && continue
    echo "$f:$line: #include \"$header\" is not next to $f; expected its path from the repository root (layer/file.hpp)"
    failures=$((failures + 1))
    continue
  fi
  place "$header"
  theirs=$layer
  [[ -n $theirs ]] || continue      # not a project header (a test's "support/...")
  [[ $theirs == "$own" ]] && continue
  [[ ${allowed[$own]} == *" $theirs "* || ${allowed[$own]} == *" $header "* ]] && continue
  echo "$f:$line: #include \"$header\" <- $own may include only:${allowed[$own]}(and $own)"
  failures=$((failures + 1))
done < <(((${#files[@]})) && grep -HnE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "${files[@]}" || true)

if ((checked < 50)); then
  echo "check_layers.sh: only $checked files found under $(pwd); expected the project's sources" >&2
  exit 1
fi

# The same rules over CMake's link graph: every library of the project takes
# the layer of its sources (one layer per library), and links only libraries of
# its own layer or of one its layer may include. Every library gets the
# repository root as its include directory, so this -- not the compiler --
# is what keeps a library from reaching above its layer through the linker.
declare -A lib_layer alias_of
libraries=0
# One line per command, "DIR<TAB>name(args)", comments dropped.
cmake_commands() {
  local f dir
  while IFS= read -r f; do
    dir=$(dirname "${f#./}")
    # Commands are case-insensitive in CMake and may have blanks before "(".
    sed 's/#.*//' "$f" | tr '\r\n' '  ' |
      { grep -ioE '(add_library|add_executable|target_link_libraries|target_include_directories|include_directories|lagrange_subcommand)[[:space:]]*\([^)]*\)' ||
        true; } |
      sed -E "s/^([A-Za-z_]+)[[:space:]]*\(/\L\1(/; s|^|$dir\t|"
  done < <(find . \( -name 'build*' -o -name .git -o -name runs -o -name tests -o -name bench -o -name fuzz \
    -o -name examples \) \
    -prune -o -name CMakeLists.txt -print | sort)
}
# place_library NAME DIR SOURCE...: its layer from its sources' (lcmtypes/: messages).
place_library() {
  local name=$1 dir=$2 src layer layers=""
  shift 2
  for src in "$@"; do
    [[ $src == *.cpp ]] || continue
    [[ $src == '${PROJECT_SOURCE_DIR}/'* ]] && src=${src#'${PROJECT_SOURCE_DIR}/'} || src=$dir/$src
    place "$src"
    if [[ -z $layer ]]; then
      echo "$dir/CMakeLists.txt: library $name compiles $src, which is in no layer"
      failures=$((failures + 1))
      continue
    fi
    [[ " $layers " == *" $layer "* ]] || layers="$layers $layer"
  done
  [[ $dir == lcmtypes ]] && layers=" messages"
  layers=${layers# }
  if [[ -z $layers ]]; then
    echo "$dir/CMakeLists.txt: library $name has no sources check_layers.sh can place"
    failures=$((failures + 1))
  elif [[ $layers == *" "* ]]; then
    echo "$dir/CMakeLists.txt: library $name mixes layers ($layers); expected one layer per library"
    failures=$((failures + 1))
  fi
  lib_layer[$name]=${layers%% *}
  libraries=$((libraries + 1))
}
links=()
links_checked=0
include_dirs=0
bad_include_dir() {
  echo "$1/CMakeLists.txt: $2 adds the include directory $3; expected only the repository root" \
    '(${PROJECT_SOURCE_DIR}), from which every include names its layer'
  failures=$((failures + 1))
}
while IFS=$'\t' read -r dir command; do
  kind=${command%%(*}
  read -ra args <<<"${command#*(}"
  args[-1]=${args[-1]%)}
  [[ ${args[-1]} == "" ]] && unset 'args[-1]'
  case $kind in
    add_library)
      name=${args[0]}
      [[ $name == *'${'* ]] && continue  # lagrange_subcommand's own add_library
      if [[ ${args[1]:-} == ALIAS ]]; then
        alias_of[$name]=${args[2]}
        continue
      fi
      place_library "$name" "$dir" "${args[@]:1}"
      ;;
    add_executable)  # a program: a process, or the front end in tools/ (or a test's)
      case $dir in
        tools | tools/*) lib_layer[${args[0]}]=frontend ;;
        *) lib_layer[${args[0]}]=process ;;
      esac
      ;;
    lagrange_subcommand)
      name=lagrange_tool_${args[0]}
      sources=() tool_links=() part=""
      for a in "${args[@]:1}"; do
        case $a in
          SOURCES | CLI | LINKS) part=$a ;;
          *) [[ $part == LINKS ]] && tool_links+=("$a") || sources+=("$a") ;;  # CLI files: its command line
        esac
      done
      place_library "$name" "$dir" "${sources[@]}"
      links+=("$dir $name ${tool_links[*]}")
      ;;
    target_link_libraries) links+=("$dir ${args[*]}") ;;
    target_include_directories | include_directories)
      # The repository root is the one include directory (and the generated
      # message headers'): every include then names its header's layer.
      first=1  # a target's name; include_directories names directories only
      [[ $kind == include_directories ]] && first=0
      for a in "${args[@]:$first}"; do
        case $a in
          PUBLIC | PRIVATE | INTERFACE | SYSTEM | BEFORE | AFTER | '${PROJECT_SOURCE_DIR}') ;;
          '${cpp_out}') [[ $dir == lcmtypes ]] || bad_include_dir "$dir" "${args[0]}" "$a" ;;
          # A third-party package's own headers (found by CMake): no layer of ours.
          '${HDF5_INCLUDE_DIRS}') ;;
          # The installed SDK's headers (lagrange/sdk/*.hpp, the sdk layer), in
          # the tree and once installed; and the message headers, as lcmtypes'.
          '$<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>' | '$<BUILD_INTERFACE:${CMAKE_BINARY_DIR}/lcmtypes/cpp>' | \
            '$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>') [[ $dir == sdk ]] || bad_include_dir "$dir" "${args[0]}" "$a" ;;
          *) bad_include_dir "$dir" "$([[ $first == 1 ]] && echo "${args[0]}" || echo "include_directories")" "$a" ;;
        esac
      done
      include_dirs=$((include_dirs + 1))
      ;;
  esac
done < <(cmake_commands)
for link in "${links[@]}"; do
  read -ra words <<<"$link"
  dir=${words[0]}
  name=${words[1]}
  [[ $name == *'${'* ]] && continue
  own=${lib_layer[$name]:-}
  [[ -n $own ]] || continue
  for target in "${words[@]:2}"; do
    target=${alias_of[$target]:-$target}
    theirs=${lib_layer[$target]:-}
    [[ -n $theirs ]] || continue  # not the project's (Eigen3::Eigen, PkgConfig::LCM, PUBLIC, ...)
    links_checked=$((links_checked + 1))
    [[ $theirs == "$own" ]] && continue
    [[ ${allowed[$own]} == *" $theirs "* ]] && continue
    echo "$dir/CMakeLists.txt: $name links $target ($theirs) <- $own may link only:${allowed[$own]}(and $own)"
    failures=$((failures + 1))
  done
done
if ((libraries < 20 || links_checked < 40 || include_dirs < 3)); then
  echo "check_layers.sh: only $libraries libraries and $links_checked links between them found in" \
    "CMakeLists.txt files; expected the project's" >&2
  exit 1
fi

if ((failures > 0)); then
  echo "$failures include(s) or link(s) point up the layers, or files or libraries are in none" >&2
  exit 1
fi
echo "layers: $checked files, every include points down; $libraries libraries, $links_checked links, every one points down; $include_dirs include directories, each the root"
