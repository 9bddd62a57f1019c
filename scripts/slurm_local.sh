#!/usr/bin/env bash
# A one-node Slurm on this machine, for the tests of tests/slurm/ and to try docs/cluster.md.
#
#   scripts/slurm_local.sh start   # munged, slurmctld, slurmd; waits until the node is idle
#   scripts/slurm_local.sh stop    # stops the three daemons by their pids
#   scripts/slurm_local.sh status  # exit 0 if the node answers
#
# Needs root and Debian's `slurm-wlm` and `munge` packages (`.ci/run` installs them). No
# systemd and no cgroups: the daemons are started directly (each daemonises, its pid in
# $STATE/*.pid), with proctrack/pgid and task/none. /etc/slurm/slurm.conf is written from
# `slurmd -C` unless a slurm.conf not written by this script is there (then the script stops:
# it never replaces a configuration it did not write). Both commands are idempotent.
set -euo pipefail

STATE=${SETTLE_SLURM_STATE:-/var/spool/settle-slurm}
CONF=/etc/slurm/slurm.conf
MARK="# Written by settle's scripts/slurm_local.sh (a one-node Slurm on localhost)."
KEY=/etc/munge/munge.key

die() { echo "slurm_local.sh: $*" >&2; exit 1; }

alive() { # alive PIDFILE: the process of PIDFILE runs
    [[ -s $1 ]] && kill -0 "$(cat "$1")" 2>/dev/null
}

answers() { # the controller answers and the node is up (idle, mixed or allocated)
    sinfo -h -o '%T' 2>/dev/null | grep -Eq '^(idle|mixed|allocated|completing)'
}

need() {
    for c in munged slurmctld slurmd sinfo sbatch; do
        command -v "$c" >/dev/null || die "\`$c\` not found: install Debian's slurm-wlm and munge (apt-get install slurm-wlm munge)"
    done
    [[ $(id -u) == 0 ]] || die "must run as root (it writes $CONF and starts the daemons)"
}

write_conf() {
    if [[ -e $CONF ]] && ! head -1 "$CONF" | grep -qF "$MARK"; then
        die "$CONF exists and was not written by this script: not replaced (a real Slurm is configured here?)"
    fi
    local host node
    host=$(hostname -s)
    node=$(slurmd -C | head -1)
    [[ $node == NodeName=* ]] || die "slurmd -C printed no node line: $node"
    mkdir -p /etc/slurm "$STATE/ctld" "$STATE/d" "$STATE/log"
    cat >"$CONF.tmp" <<EOF
$MARK
ClusterName=settle-local
SlurmctldHost=$host
AuthType=auth/munge
ProctrackType=proctrack/pgid
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$STATE/ctld
SlurmdSpoolDir=$STATE/d
SlurmctldPidFile=$STATE/slurmctld.pid
SlurmdPidFile=$STATE/slurmd.pid
SlurmctldLogFile=$STATE/log/slurmctld.log
SlurmdLogFile=$STATE/log/slurmd.log
ReturnToService=2
MinJobAge=600
KillWait=5
# Start a pending job as soon as a CPU frees (by default a batch job waits up to 3 s
# for the next scheduling pass: a 16-task array on 2 cores took 3 s per pair of tasks).
SchedulerParameters=batch_sched_delay=0,sched_min_interval=0
$node State=UNKNOWN
PartitionName=local Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
    mv "$CONF.tmp" "$CONF"
}

start_munge() {
    if alive /run/munge/munged.pid; then return; fi
    if [[ ! -s $KEY ]]; then
        mkdir -p /etc/munge
        head -c 1024 /dev/urandom >"$KEY"
    fi
    chown munge:munge "$KEY"
    chmod 400 "$KEY"
    mkdir -p /run/munge /var/log/munge /var/lib/munge
    chown munge:munge /run/munge /var/log/munge /var/lib/munge
    if command -v runuser >/dev/null; then
        runuser -u munge -- munged
    else
        su -s /bin/sh munge -c munged
    fi
}

start() {
    need
    if alive "$STATE/slurmctld.pid" && alive "$STATE/slurmd.pid" && answers; then
        echo "slurm_local.sh: already running ($(sinfo -h -o '%N %T'))"
        return
    fi
    write_conf
    start_munge
    alive "$STATE/slurmctld.pid" || slurmctld -c
    alive "$STATE/slurmd.pid" || slurmd
    for _ in $(seq 60); do
        if answers; then
            echo "slurm_local.sh: started ($(sinfo -h -o '%N %T'); logs in $STATE/log)"
            return
        fi
        sleep 0.5
    done
    die "the node did not come up within 30 s; see $STATE/log/ and \`sinfo -R\`"
}

stop_pid() { # stop_pid PIDFILE NAME
    alive "$1" || return 0
    local pid
    pid=$(cat "$1")
    kill "$pid"
    for _ in $(seq 50); do
        kill -0 "$pid" 2>/dev/null || return 0
        sleep 0.2
    done
    kill -9 "$pid" 2>/dev/null || true
}

stop() {
    stop_pid "$STATE/slurmd.pid" slurmd
    stop_pid "$STATE/slurmctld.pid" slurmctld
    stop_pid /run/munge/munged.pid munged
    echo "slurm_local.sh: stopped"
}

case ${1:-} in
    start) start ;;
    stop) stop ;;
    status) answers ;;
    *) die "usage: scripts/slurm_local.sh start|stop|status" ;;
esac
