#!/usr/bin/env bash
# Two hosts on one machine: two network namespaces joined by a veth pair,
# multicast routed over it, LCM with TTL 1. Host A runs the plant and the
# actuator, host B the controller and the logger, each under its own
# `lagrange run --processes ...`. Needs root (or CAP_NET_ADMIN and
# CAP_SYS_ADMIN) and runs inside the test suite's own namespace, so nothing
# touches the machine's interfaces.
#
# usage: two_hosts.sh BIN_DIR CONFIG OUT_DIR [extra lagrange run arguments]
# Writes OUT_DIR/a, OUT_DIR/b (each host's run directory), OUT_DIR/{a,b}.out
# (each launcher's output) and prints "exit codes: A B".
set -euo pipefail
bin=$1 config=$2 out=$3
shift 3
mkdir -p "$out"

# Each host is the network namespace of a process that sleeps. Unnamed
# namespaces (unlike `ip netns add`) leave nothing behind in /run when the
# test ends: they die with their sleeper.
unshare -n sleep 600 &
host_a=$!
unshare -n sleep 600 &
host_b=$!
trap 'kill $host_a $host_b 2>/dev/null || true' EXIT
own=$(readlink /proc/self/ns/net)
for pid in $host_a $host_b; do
  for _ in $(seq 100); do
    [[ $(readlink /proc/$pid/ns/net 2>/dev/null) != "$own" ]] && break
    sleep 0.02
  done
done
on() { local pid=$1; shift; nsenter --net=/proc/$pid/ns/net "$@"; }

ip link add veth-a type veth peer name veth-b
ip link set veth-a netns "$host_a"
ip link set veth-b netns "$host_b"
for side in "a $host_a 10.77.0.1" "b $host_b 10.77.0.2"; do
  read -r name pid address <<<"$side"
  on "$pid" ip link set lo up
  on "$pid" ip addr add "$address/24" dev "veth-$name"
  on "$pid" ip link set "veth-$name" up multicast on
  on "$pid" ip route add 224.0.0.0/4 dev "veth-$name"
done

url="udpm://239.255.76.67:7711?ttl=1"
# One secret for both hosts, as a user would copy it to each (docs/deployment.md).
key="$out/run.key"
rm -f "$key"
"$bin/lagrange" keygen "$key"
on "$host_b" "$bin/lagrange" run "$config" -o "$out/b" --no-netns --lcm-url "$url" --key-file "$key" \
  --processes controller,logger "$@" >"$out/b.out" 2>&1 &
run_b=$!
on "$host_a" "$bin/lagrange" run "$config" -o "$out/a" --no-netns --lcm-url "$url" --key-file "$key" \
  --processes plant,actuator "$@" >"$out/a.out" 2>&1 &
run_a=$!
code_a=0 code_b=0
wait $run_a || code_a=$?
wait $run_b || code_b=$?
echo "exit codes: $code_a $code_b"
