#!/usr/bin/env bash
# A private single-node Slurm cluster (munged + slurmctld + slurmd) in one folder, for testing the
# scripts of `crowdlab plan --emit slurm` with real sbatch. Nothing outside DIR is touched: the daemons
# run as the current user with their own munge key, socket, ports, state and logs.
# Usage: scripts/slurm-single-node.sh start DIR   -> prints "export SLURM_CONF=DIR/slurm.conf"
#        scripts/slurm-single-node.sh stop DIR
# Needs Debian's slurm-wlm and munge (scripts/install-deps.sh --test). Exits non-zero, with the daemon
# logs on stderr, when the cluster does not come up within 20 s.
set -euo pipefail
cmd=${1:?usage: $0 start|stop DIR}
dir=$(realpath -m "${2:?usage: $0 start|stop DIR}")

stop() {
  for pid_file in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munge/munged.pid"; do
    if [[ -s $pid_file ]]; then kill "$(cat "$pid_file")" 2>/dev/null || true; fi
  done
}

if [[ $cmd == stop ]]; then
  stop
  exit 0
fi
[[ $cmd == start ]] || { echo "usage: $0 start|stop DIR" >&2; exit 2; }

mkdir -p "$dir"/{state,spool,log,munge}
chmod 700 "$dir/munge"
head -c 1024 /dev/urandom >"$dir/munge/munge.key"
chmod 600 "$dir/munge/munge.key"
/usr/sbin/munged --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
  --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/seed" -f

# Ports derived from this shell's pid so that concurrent test runs do not collide.
port=$((20000 + ($$ % 2000) * 2))
host=$(hostname -s)
mem_mb=$(($(awk '/MemTotal/{print $2}' /proc/meminfo) / 1024 - 256))
cat >"$dir/slurm.conf" <<CONF
ClusterName=crowdlabtest
SlurmctldHost=$host
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
MpiDefault=none
NodeName=$host CPUs=$(nproc) RealMemory=$mem_mb State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$dir/slurm.conf
/usr/sbin/slurmctld -f "$SLURM_CONF"
/usr/sbin/slurmd -f "$SLURM_CONF"
for _ in $(seq 1 80); do
  if sinfo -h -o %t 2>/dev/null | grep -q idle; then
    echo "export SLURM_CONF=$SLURM_CONF"
    exit 0
  fi
  sleep 0.25
done
echo "slurm-single-node: the node did not become idle within 20 s" >&2
cat "$dir"/log/*.log "$dir/munge/munged.log" >&2 || true
stop
exit 1
