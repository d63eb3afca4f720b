#!/usr/bin/env bash
# A one-node SLURM cluster in a folder, to try jobs/slurm/ on this machine and to test it:
# munged, slurmctld and slurmd with their key, state, logs and sockets in DIR, on loopback ports
# of their own; nothing under /etc is read or changed. Needs Debian's slurm-wlm and munge
# (scripts/install-deps.sh). Tested as root; SLURM and munge run as the user who starts them.
#   scripts/slurm-one-node.sh start DIR   # then: export SLURM_CONF=DIR/slurm.conf; sbatch ...
#   scripts/slurm-one-node.sh stop DIR    # cancels its jobs, stops the daemons
set -euo pipefail

usage="usage: slurm-one-node.sh start|stop DIR"
action=${1:?$usage}
dir=$(realpath -m "${2:?$usage}")
export SLURM_CONF=$dir/slurm.conf
export PATH=$PATH:/usr/sbin  # munged, slurmctld, slurmd (not on a user's PATH in Debian)

# Seconds a job's processes get between SIGTERM and SIGKILL when it is cancelled or times out,
# and after which a requeued job may start again (SLURM's default, 120 s, would slow the tests).
kill_wait=30
requeue_delay=5

die() {
  echo "slurm-one-node: $*" >&2
  for f in "$dir"/log/*.log; do [[ -f $f ]] && { echo "== $f" >&2; tail -n 20 "$f" >&2; }; done
  exit 1
}

# Two free loopback ports, so that clusters of other users or runs do not collide.
free_ports() {
  /usr/bin/python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))'
}

write_conf() {
  local host user ports
  host=$(hostname -s)
  user=$(id -un)
  read -r -a ports < <(free_ports)
  cat >"$SLURM_CONF" <<EOF
# One node, this machine, on loopback; written by scripts/slurm-one-node.sh.
ClusterName=grip
SlurmctldHost=$host(127.0.0.1)
SlurmUser=$user
SlurmdUser=$user
SlurmctldPort=${ports[0]}
SlurmdPort=${ports[1]}
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket,cred_expire=$requeue_delay
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
# No cgroups: processes are tracked by their parentage, tasks are not bound to cores.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/builtin
SchedulerParameters=sched_interval=2
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
KillWait=$kill_wait
MinJobAge=3600
NodeName=grip0 NodeHostname=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=grip Nodes=grip0 Default=YES MaxTime=INFINITE State=UP
EOF
}

start() {
  for program in munged slurmctld slurmd sbatch; do
    command -v "$program" >/dev/null || die "$program not found: run scripts/install-deps.sh"
  done
  mkdir -p "$dir"/{munge,state,spool,run,log}
  chmod 700 "$dir/munge"
  head -c 1024 /dev/urandom >"$dir/munge/munge.key"
  chmod 400 "$dir/munge/munge.key"
  write_conf
  # --force: munged otherwise refuses a socket folder that is not world-searchable.
  munged --force --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
    --log-file="$dir/log/munged.log" --pid-file="$dir/run/munged.pid" \
    --seed-file="$dir/munge/munged.seed" || die "munged did not start"
  slurmctld -f "$SLURM_CONF" || die "slurmctld did not start"
  slurmd -f "$SLURM_CONF" -N grip0 || die "slurmd did not start"
  for _ in $(seq 1 150); do
    [[ $(sinfo -h -n grip0 -o %T 2>/dev/null) == idle ]] && return 0
    sleep 0.2
  done
  die "the node grip0 did not come up idle within 30 s"
}

# Ends the process of a pid file in DIR/run: SIGTERM, then SIGKILL after $2 s.
end_process() {
  local pid_file=$dir/run/$1 pid
  [[ -f $pid_file ]] || return 0
  pid=$(cat "$pid_file")
  kill "$pid" 2>/dev/null || return 0
  for _ in $(seq 1 $(($2 * 5))); do
    kill -0 "$pid" 2>/dev/null || return 0
    sleep 0.2
  done
  kill -KILL "$pid" 2>/dev/null || true
}

stop() {
  [[ -f $SLURM_CONF ]] || return 0
  # scontrol shutdown would leave the processes of running jobs behind: cancel the jobs first.
  squeue -h -o %i 2>/dev/null | xargs -r scancel
  for _ in $(seq 1 $(((kill_wait + 15) * 5))); do
    [[ -z $(squeue -h -o %i 2>/dev/null) ]] && break
    sleep 0.2
  done
  end_process slurmd.pid 20
  end_process slurmctld.pid 20
  end_process munged.pid 10
}

case $action in
  start) start ;;
  stop) stop ;;
  *) echo "$usage" >&2; exit 2 ;;
esac
