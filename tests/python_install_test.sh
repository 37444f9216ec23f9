#!/usr/bin/env bash
# `pip install ./python` works offline with Debian's own Python packages
# (python3-venv, python3-pip, python3-setuptools, python3-wheel): in a fresh
# virtual environment, from a copy of python/, and the installed package
# then imports from anywhere and reaches liblcm.
set -euo pipefail
root=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp -r "$root/python" "$work/src"
/usr/bin/python3 -m venv --system-site-packages "$work/venv"
"$work/venv/bin/pip" install --quiet --disable-pip-version-check --no-cache-dir --no-build-isolation --no-index \
  "$work/src"  # nothing from the network, nothing left in ~/.cache
rm -rf "$work/src"  # the installed copy, not the source, must be what imports
cd "$work"
"$work/venv/bin/python" - "$work/venv" <<'PY'
import sys, lagrange, lagrange.lcm, lagrange.log, lagrange.external
assert lagrange.__file__.startswith(sys.argv[1]), lagrange.__file__
got = []
with lagrange.lcm.LCM("memq://") as lc:
    lc.subscribe("CH", lambda channel, data: got.append(data))
    lc.publish("CH", b"ok")
    lc.handle_timeout(100)
assert got == [b"ok"], got
print("installed lagrange", lagrange.__version__, "at", lagrange.__file__)
PY
