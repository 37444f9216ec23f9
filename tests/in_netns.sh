#!/usr/bin/env bash
# Runs a command inside a private network namespace whose loopback carries
# multicast, so LCM traffic of tests never touches the machine's interfaces.
set -euo pipefail
if [[ "${LAGRANGE_TEST_NETNS:-}" != 1 ]]; then
  export LAGRANGE_TEST_NETNS=1
  if [[ $(id -u) -eq 0 ]]; then exec unshare -n -- "$0" "$@"; else exec unshare -rn -- "$0" "$@"; fi
fi
ip=$(command -v ip || echo /usr/sbin/ip)
"$ip" link set lo up
"$ip" link set lo multicast on
"$ip" route add 224.0.0.0/4 dev lo
exec "$@"
