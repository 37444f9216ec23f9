#!/usr/bin/env bash
# Writes the Python message classes of python/lagrange/ from lcmtypes/*.lcm
# with lcm-gen -p (Debian's liblcm-bin), patched for Python 3:
#   scripts/generate-python-types.sh            into python/lagrange/
#   scripts/generate-python-types.sh DIR        into DIR (the test that the
#                                               checked-in files are current)
# The patch: lcm-gen 1.3 decodes a boolean array as map(bool, ...), a
# one-shot iterator in Python 3 (a message decoded from a log could not be
# encoded again, nor its field read twice); made a list.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/python/lagrange}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
lcm-gen -p --ppath "$work" "$root"/lcmtypes/*.lcm >/dev/null
mkdir -p "$out"
for f in "$work"/lagrange/*_t.py; do
  sed -E 's/^( +self\.[A-Za-z0-9_]+ = )map\(bool, (.*)\)$/\1list(map(bool, \2))/' "$f" >"$out/$(basename "$f")"
done
