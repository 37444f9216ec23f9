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
status=0
"$@" || status=$?
# What a crashed test left behind in this namespace -- a browser whose test
# aborted before closing it, a daemon -- ends with the suite instead of
# running on (a headless chromium's GPU process keeps a core busy).
here=$(readlink /proc/$$/ns/net)
for proc in /proc/[0-9]*; do
  pid=${proc#/proc/}
  if [[ $pid != "$$" && $(readlink "$proc/ns/net" 2>/dev/null || true) == "$here" ]]; then
    kill -KILL "$pid" 2>/dev/null || true
  fi
done
exit "$status"
