#!/usr/bin/env bash
# Writes the Python message classes of python/lagrange/ from lcmtypes/*.lcm
# with lcm-gen -p (Debian's liblcm-bin), patched:
#   scripts/generate-python-types.sh            into python/lagrange/
#   scripts/generate-python-types.sh DIR        into DIR (the test that the
#                                               checked-in files are current)
# The patches:
#  - lcm-gen 1.3 decodes a boolean array as map(bool, ...), a one-shot
#    iterator in Python 3 (a message decoded from a log could not be encoded
#    again, nor its field read twice): made a list;
#  - a decoder loops over a count read from the message: a hostile message
#    with rows of zero width (chain_order 2^31 - 1, num_joints 0) would loop
#    for minutes and fill the memory with empty rows. As the C++ decoders do
#    (transport/safe_decode.hpp), a count larger than the message's bytes is
#    refused (ValueError) before the loop.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/python/lagrange}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
lcm-gen -p --ppath "$work" "$root"/lcmtypes/*.lcm >/dev/null
mkdir -p "$out"
for f in "$work"/lagrange/*_t.py; do
  python3 - "$f" "$out/$(basename "$f")" <<'PY'
import re, sys
source, target = sys.argv[1], sys.argv[2]
lines, out, decoding = open(source).read().split("\n"), [], False
for line in lines:
    if re.match(r"^    def ", line):
        decoding = line.startswith("    def _decode_one(")
    line = re.sub(r"^( +self\.[A-Za-z0-9_]+ = )map\(bool, (.*)\)$", r"\1list(map(bool, \2))", line)
    m = re.match(r"^( +)for (i[0-9]+) in range\(self\.([A-Za-z0-9_]+)\):$", line)
    if decoding and m:
        indent, count = m.group(1), m.group(3)
        out.append("%sif not 0 <= self.%s <= len(buf.getbuffer()): raise ValueError(\"%s larger than the message\")"
                   % (indent, count, count))
    out.append(line)
open(target, "w").write("\n".join(out))
PY
done
