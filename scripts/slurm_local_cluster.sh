#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for trying scripts/slurm_sweep.sh without a real cluster
# (and for the `slow` test slurm_sweep, scripts/slurm_check.sh). Needs the Debian packages slurm-wlm and
# munge (scripts/setup.sh installs them) and root (slurmd runs jobs as their users).
#   scripts/slurm_local_cluster.sh start DIR   write a configuration into DIR, start munged, slurmctld and
#                                              slurmd on localhost, wait until the node takes jobs
#   scripts/slurm_local_cluster.sh stop DIR    stop them
# Every file (configuration, key, sockets, state, logs) stays in DIR, nothing under /etc or /var; point
# Slurm's commands at it with `export SLURM_CONF=DIR/slurm.conf` (start prints it).
set -euo pipefail
usage() { echo "usage: $0 start|stop DIR" >&2; exit 2; }
[ $# -eq 2 ] || usage
action=$1
dir=$(realpath -m "$2")
case "$dir" in *[[:space:]]*) echo "$0: DIR '$dir': no blanks please (it is written into slurm.conf)" >&2; exit 2 ;; esac

stop() {
  for daemon in slurmd slurmctld munged; do
    [ -f "$dir/$daemon.pid" ] || continue
    local pid
    pid=$(cat "$dir/$daemon.pid")
    # Only the daemon this folder started (a stale pid file may name another process by now).
    if [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$daemon" ]; then
      kill "$pid" 2>/dev/null || true
      for _ in $(seq 1 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    fi
    rm -f "$dir/$daemon.pid"
  done
}

write_config() {
  local cpus memory_mb
  cpus=$(nproc)
  memory_mb=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 - 1024 ))
  mkdir -p "$dir/state" "$dir/spool" "$dir/logs"
  cat > "$dir/slurm.conf" <<CONF
ClusterName=sortcell-local
SlurmctldHost=localhost
SlurmUser=$(id -un)
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge.socket
CredType=cred/munge
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/logs/slurmctld.log
SlurmdLogFile=$dir/logs/slurmd.log
SlurmctldPort=${SORTCELL_SLURMCTLD_PORT:-6817}
SlurmdPort=${SORTCELL_SLURMD_PORT:-6818}
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
NodeName=localhost CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=local Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
}

start() {
  [ "$(id -u)" -eq 0 ] || { echo "$0: needs root (slurmd runs jobs as their users)" >&2; exit 77; }
  for tool in munged mungekey slurmctld slurmd sinfo; do
    command -v "$tool" >/dev/null || { echo "$0: '$tool' not found: install the Debian packages slurm-wlm and munge" >&2; exit 77; }
  done
  stop
  mkdir -p "$dir"
  write_config
  [ -f "$dir/munge.key" ] || mungekey --create --keyfile="$dir/munge.key" >/dev/null
  chmod 600 "$dir/munge.key"
  munged --force --key-file="$dir/munge.key" --socket="$dir/munge.socket" --pid-file="$dir/munged.pid" \
    --log-file="$dir/logs/munged.log" --seed-file="$dir/munge.seed"
  export SLURM_CONF=$dir/slurm.conf
  slurmctld -c -f "$SLURM_CONF"
  slurmd -f "$SLURM_CONF"
  for _ in $(seq 1 60); do
    if sinfo -h -o %T 2>/dev/null | grep -qE '^(idle|mixed|allocated)'; then
      echo "Slurm is up: export SLURM_CONF=$SLURM_CONF"
      return 0
    fi
    sleep 1
  done
  echo "$0: the node did not come up within 60 s; logs in $dir/logs" >&2
  stop
  exit 1
}

case "$action" in
  start) start ;;
  stop) stop ;;
  *) usage ;;
esac
