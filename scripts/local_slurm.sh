#!/usr/bin/env bash
# A one-node Slurm cluster on localhost, for the farm tests (tests/farm_slurm_test.sh) and
# for trying `globular farm` without a cluster. Debian's slurmctld, slurmd and munged
# (WITH_SLURM=1 scripts/setup.sh installs them), their configuration, munge key, state
# and logs all in one temporary folder; no cgroups (proctrack/linuxproc, task/none), no
# accounting database (so sacct has nothing to say; squeue and the files do).
#   scripts/local_slurm.sh start [DIR]   then: export SLURM_CONF=DIR/slurm.conf
#   scripts/local_slurm.sh stop [DIR]    stops the daemons it started and removes DIR
# DIR defaults to /tmp/globular-slurm. The daemons run as the user who starts them (root
# in CI and here; jobs then run as that user); the ports are 16817 and 16818 unless
# GLOBULAR_SLURM_PORT (the controller's; slurmd's is one above).
set -euo pipefail
cmd=${1:-}
dir=${2:-/tmp/globular-slurm}
port=${GLOBULAR_SLURM_PORT:-16817}

stop() {
    # Only the daemons this script started, by the pids they recorded.
    for name in slurmd slurmctld munged; do
        pidfile=$dir/run/$name.pid
        [[ -f $pidfile ]] || continue
        pid=$(cat "$pidfile")
        if [[ -n $pid ]] && kill -0 "$pid" 2>/dev/null; then
            kill "$pid" 2>/dev/null || true
            for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
            kill -9 "$pid" 2>/dev/null || true
        fi
    done
    rm -rf "$dir"
}

start() {
    for program in munged slurmctld slurmd sinfo; do
        command -v "$program" >/dev/null || {
            echo "local_slurm: $program is not installed (WITH_SLURM=1 scripts/setup.sh," \
                 "or apt-get install slurm-wlm munge)" >&2
            exit 3
        }
    done
    [[ -e $dir ]] && stop
    mkdir -p "$dir"/{munge,run,log,ctld,spool}
    chmod 700 "$dir/munge"
    head -c 1024 /dev/urandom >"$dir/munge/munge.key"
    chmod 400 "$dir/munge/munge.key"
    munged --force --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
        --pid-file="$dir/run/munged.pid" --log-file="$dir/log/munged.log" \
        --seed-file="$dir/munge/munge.seed"
    host=$(hostname -s)
    user=$(id -un)
    cpus=$(nproc)
    cat >"$dir/slurm.conf" <<CONF
ClusterName=globular-local
SlurmctldHost=$host(127.0.0.1)
SlurmUser=$user
SlurmdUser=$user
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/ctld
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1,bf_interval=1,defer_batch
MpiDefault=none
ReturnToService=2
MinJobAge=3600
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=1024 State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
    export SLURM_CONF=$dir/slurm.conf
    slurmctld -f "$SLURM_CONF"
    slurmd -f "$SLURM_CONF"
    for _ in $(seq 150); do
        state=$(sinfo --noheader --format=%T 2>/dev/null || true)
        if [[ $state == idle* ]]; then
            echo "local_slurm: node $host idle; export SLURM_CONF=$SLURM_CONF"
            return 0
        fi
        sleep 0.2
    done
    echo "local_slurm: the node did not come up (state '${state:-none}'); logs in $dir/log:" >&2
    tail -n 20 "$dir"/log/*.log >&2 || true
    exit 1
}

case $cmd in
start) start ;;
stop) stop ;;
*) echo "usage: $0 start|stop [DIR]" >&2; exit 2 ;;
esac
