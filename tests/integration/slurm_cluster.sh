#!/usr/bin/env bash
# A one-node Slurm cluster from Debian's packages (munge, slurmctld, slurmd)
# for the sweep's Slurm test, inside the caller's private network namespace:
#   slurm_cluster.sh start DIR   configure and start it in DIR, wait until the node is idle;
#                                prints SLURM_CONF=DIR/slurm.conf for the clients
#   slurm_cluster.sh stop DIR    stop every daemon it started, remove its link
# Run as root inside a network namespace of its own (tests/in_netns.sh); it
# refuses to start on the machine's network. The namespace gets a veth pair
# with an address, 10.213.0.1: with nothing but `lo`, glibc's getaddrinfo
# (AI_ADDRCONFIG) resolves no name and Slurm's daemons fail with "Unable to
# resolve" (docs/sweeps.md). Everything -- key, sockets, state, logs -- lives in DIR.
set -euo pipefail
cmd=${1:?usage: slurm_cluster.sh start|stop DIR}
dir=${2:?usage: slurm_cluster.sh start|stop DIR}
ip=$(command -v ip || echo /usr/sbin/ip)
addr=10.213.0.1

stop() {
  for pidfile in "$dir"/slurmd.pid "$dir"/slurmctld.pid "$dir"/munged.pid; do
    [[ -f $pidfile ]] || continue
    pid=$(cat "$pidfile")
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
    rm -f "$pidfile"
  done
  # The namespace's link goes too (deleting one end removes the pair).
  "$ip" link del lgslurm0 2>/dev/null || true
}

if [[ $cmd == stop ]]; then
  stop
  exit 0
fi
[[ $cmd == start ]] || { echo "slurm_cluster.sh: unknown command '$cmd'; expected start or stop" >&2; exit 2; }

for tool in munged slurmctld slurmd sinfo sbatch; do
  command -v "$tool" >/dev/null || {
    echo "slurm_cluster.sh: $tool not found; expected Debian's munge, slurmctld, slurmd and slurm-client" \
      "(scripts/setup.sh installs them)" >&2
    exit 1
  }
done
if [[ "${LAGRANGE_TEST_NETNS:-}" != 1 ]]; then
  echo "slurm_cluster.sh: refusing to start daemons outside a private network namespace; run it under tests/in_netns.sh" >&2
  exit 1
fi

mkdir -p "$dir"/state "$dir"/spool "$dir"/munge
chmod 700 "$dir" "$dir"/munge
host=$(hostname -s)

# The namespace's own link with an address (see above).
if ! "$ip" -o addr show | grep -q " $addr/"; then
  "$ip" link add lgslurm0 type veth peer name lgslurm1
  "$ip" addr add "$addr/24" dev lgslurm0
  "$ip" link set lgslurm0 up
  "$ip" link set lgslurm1 up
fi

# munge: a fresh key, its own socket; --force because root runs it here.
dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$dir/munge/munge.key"
munged --force --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.sock" \
  --pid-file="$dir/munged.pid" --log-file="$dir/munged.log" --seed-file="$dir/munge/munge.seed"

# What slurmd finds on this machine, so the node is not drained for claiming more.
hardware=$(slurmd -C | head -1 | sed -e 's/^NodeName=[^ ]* //')
cat > "$dir/slurm.conf" <<CONF
ClusterName=lagrange-test
SlurmctldHost=$host($addr)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.sock
SlurmctldPort=6817
SlurmdPort=6818
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=$host NodeAddr=$addr $hardware State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$dir/slurm.conf"
slurmctld -i
slurmd

for _ in $(seq 300); do
  state=$(sinfo -h -N -o %t 2>/dev/null || true)
  if [[ $state == idle ]]; then
    echo "SLURM_CONF=$SLURM_CONF"
    exit 0
  fi
  sleep 0.2
done
echo "slurm_cluster.sh: the node did not become idle in 60 s (sinfo: '${state:-}'); logs in $dir" >&2
tail -5 "$dir"/slurmctld.log "$dir"/slurmd.log >&2 || true
stop
exit 1
