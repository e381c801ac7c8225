#!/usr/bin/env bash
# A real single-node Slurm cluster for tests, from Debian's packages (slurm-wlm and munge), run
# as root on the test machine.
#
#   cluster.sh start STATE_DIR   install the packages if missing, start munged (unless one already
#                                answers), write STATE_DIR/slurm.conf, start slurmctld and slurmd,
#                                wait until the node is idle. Prints one line to stdout:
#                                `export SLURM_CONF=STATE_DIR/slurm.conf` (also in STATE_DIR/env).
#   cluster.sh stop STATE_DIR    cancel what is still queued, stop slurmd and slurmctld by their pid
#                                files, and munged too if `start` started it. Idempotent.
#   cluster.sh status STATE_DIR  daemons, node and queue.
#
# Everything this cluster owns lives under STATE_DIR (config, controller state, slurmd spool, pid
# files, logs); each start empties it first, so job ids start at 1 again. /etc/slurm/slurm.conf is
# never written: daemons get `-f`, clients `SLURM_CONF`. Ports are the standard 6817/6818 unless
# they are taken, then the next free pair. Needs root (Slurm runs jobs as root here: SlurmUser=root).
#
# Environment: SOLSIM_SLURM_START_TIMEOUT (seconds to wait for an idle node, default 60).
set -euo pipefail

usage() {
    echo "usage: $0 start|stop|status STATE_DIR" >&2
    exit 2
}

log() { echo "cluster.sh: $*" >&2; }

die() {
    log "error: $*"
    exit 1
}

[[ $# -eq 2 ]] || usage
cmd=$1
if [[ ! -d $2 ]]; then
    case $cmd in
    start) mkdir -p "$2" ;;
    stop) exit 0 ;; # nothing was started there
    status)
        echo "no cluster state in $2"
        exit 1
        ;;
    *) usage ;;
    esac
fi
S=$(cd "$2" && pwd)
CONF=$S/slurm.conf
RUN=$S/run
LOGS=$S/log
HOST=$(hostname -s)
PACKAGES=(slurmctld slurmd slurm-client munge)
MUNGE_PID_FILE=/run/munge/munged.pid

# Whether process PID is alive and is COMM (a recycled pid is not ours to kill; a zombie is gone
# for our purposes: PID 1 here may never reap it).
pid_alive() {
    local pid=$1 comm=$2
    [[ $(cat "/proc/$pid/comm" 2>/dev/null) == "$comm" ]] || return 1
    [[ $(cut -d' ' -f3 "/proc/$pid/stat" 2>/dev/null) != Z ]]
}

# The pid in FILE if that process is alive and is COMM.
live_pid() {
    local file=$1 comm=$2 pid
    [[ -s $file ]] || return 1
    pid=$(<"$file")
    [[ $pid =~ ^[0-9]+$ ]] || return 1
    pid_alive "$pid" "$comm" || return 1
    echo "$pid"
}

# Sends TERM to the process in FILE (if alive and COMM), waits up to 15 s for it to end (by its
# pid: a daemon may remove its pid file before it has finished), then KILL.
stop_pid() {
    local file=$1 comm=$2 pid i
    pid=$(live_pid "$file" "$comm") || return 0
    log "stopping $comm (pid $pid)"
    kill -TERM "$pid" 2>/dev/null || true
    for ((i = 0; i < 150; i++)); do
        pid_alive "$pid" "$comm" || return 0
        sleep 0.1
    done
    log "$comm (pid $pid) ignored TERM for 15 s: KILL"
    kill -KILL "$pid" 2>/dev/null || true
    for ((i = 0; i < 50; i++)); do
        pid_alive "$pid" "$comm" || return 0
        sleep 0.1
    done
    log "$comm (pid $pid) still alive after KILL"
}

munge_answers() { munge -n 2>/dev/null | unmunge >/dev/null 2>&1; }

# TCP ports something listens on (IPv4 and IPv6), from /proc: no tool needed.
listening_ports() {
    local _ local_addr _r state _rest
    cat /proc/net/tcp /proc/net/tcp6 2>/dev/null |
        while read -r _ local_addr _r state _rest; do
            [[ $state == 0A ]] && echo $((16#${local_addr##*:}))
        done | sort -un
}

free_port_pair() {
    local used p
    used=" $(listening_ports | tr '\n' ' ') "
    for ((p = 6817; p < 6817 + 400; p += 2)); do
        [[ $used == *" $p "* || $used == *" $((p + 1)) "* ]] || {
            echo "$p"
            return 0
        }
    done
    die "no free port pair in 6817..7217"
}

show_logs() {
    local f
    for f in "$LOGS"/slurmctld.log "$LOGS"/slurmd.log "$LOGS"/slurmctld.out "$LOGS"/slurmd.out; do
        [[ -s $f ]] || continue
        echo "----- $f (last 40 lines) -----" >&2
        tail -n 40 "$f" >&2
    done
}

install_packages() {
    local missing=() p
    for p in "${PACKAGES[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' ||
            missing+=("$p")
    done
    [[ ${#missing[@]} -eq 0 ]] && return 0
    command -v apt-get >/dev/null || die "Slurm packages missing (${missing[*]}) and no apt-get"
    log "installing ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get -o DPkg::Lock::Timeout=300 update -qq >&2 || die "apt-get update failed"
    apt-get -o DPkg::Lock::Timeout=300 install -y -qq --no-install-recommends "${PACKAGES[@]}" >&2 ||
        die "apt-get install ${PACKAGES[*]} failed"
}

# Starts munged as the munge user unless one already answers; records a munged we started.
start_munge() {
    rm -f "$S/munged.started-by-us"
    if munge_answers; then
        log "munged already running: leaving it alone"
        return 0
    fi
    if [[ ! -s /etc/munge/munge.key ]]; then
        mungekey --create --keyfile=/etc/munge/munge.key >&2 || die "mungekey --create failed"
        chown munge:munge /etc/munge/munge.key
        chmod 0400 /etc/munge/munge.key
    fi
    # No systemd here to create the runtime directory.
    install -d -o munge -g munge -m 0755 /run/munge
    # --force: a stale socket from a munged that died is not a reason to refuse.
    su -s /bin/sh munge -c '/usr/sbin/munged --force' >&2 ||
        die "munged did not start (see /var/log/munge/munged.log)"
    local i pid
    for ((i = 0; i < 100; i++)); do
        munge_answers && break
        sleep 0.1
    done
    munge_answers || {
        tail -n 20 /var/log/munge/munged.log >&2 2>/dev/null || true
        die "munged started but 'munge -n | unmunge' fails"
    }
    pid=$(live_pid "$MUNGE_PID_FILE" munged) || die "munged answers but $MUNGE_PID_FILE is not its pid"
    echo "$pid" >"$S/munged.started-by-us"
}

# The clients resolve the controller, slurmd its own node name.
fix_hostname() {
    getent hosts "$HOST" >/dev/null && return 0
    log "$HOST does not resolve: adding '127.0.0.1 $HOST' to /etc/hosts"
    echo "127.0.0.1 $HOST" >>/etc/hosts
}

write_conf() {
    local port=$1 mem_mib cpus
    cpus=$(nproc)
    mem_mib=$(awk '/^MemTotal:/ { printf "%d", $2 / 1024 * 0.9 }' /proc/meminfo)
    cat >"$CONF" <<EOF
# Written by tests/slurm/cluster.sh: a single-node cluster whose files all live in $S.
ClusterName=solsimtest
SlurmctldHost=$HOST
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
StateSaveLocation=$S/ctld-state
SlurmdSpoolDir=$S/slurmd-spool
SlurmctldPidFile=$RUN/slurmctld.pid
SlurmdPidFile=$RUN/slurmd.pid
SlurmctldLogFile=$LOGS/slurmctld.log
SlurmdLogFile=$LOGS/slurmd.log
# No cgroups, no accounting in these VMs.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
# Without it array tasks start in 3-second waves.
SchedulerParameters=batch_sched_delay=0
# Finished jobs stay visible to 'scontrol show job' this long (seconds).
MinJobAge=600
# A job whose dependency can never be met (afterok on a failed job) is cancelled, not left pending.
DependencyParameters=kill_invalid_depend
NodeName=$HOST CPUs=$cpus RealMemory=$mem_mib State=UNKNOWN
PartitionName=debug Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
EOF
}

start() {
    [[ $(id -u) -eq 0 ]] || die "must run as root"
    # A previous start on this STATE_DIR that was never stopped.
    if live_pid "$RUN/slurmctld.pid" slurmctld >/dev/null || live_pid "$RUN/slurmd.pid" slurmd >/dev/null; then
        log "daemons of an earlier start still running in $S: stopping them first"
        stop
    fi
    install_packages
    fix_hostname
    start_munge

    # A clean slate: no job ids or node state from an earlier start.
    rm -rf "$S/ctld-state" "$S/slurmd-spool" "$RUN" "$LOGS" "$CONF" "$S/env"
    mkdir -p "$S/ctld-state" "$S/slurmd-spool" "$RUN" "$LOGS"
    local port
    port=$(free_port_pair)
    write_conf "$port"
    export SLURM_CONF=$CONF

    local deadline=$((SECONDS + ${SOLSIM_SLURM_START_TIMEOUT:-60}))
    fail() {
        show_logs
        stop >&2 || true
        die "$*"
    }
    # Both daemonize; a configuration error makes them exit non-zero right here.
    slurmctld -f "$CONF" >"$LOGS/slurmctld.out" 2>&1 || fail "slurmctld did not start"
    slurmd -f "$CONF" >"$LOGS/slurmd.out" 2>&1 || fail "slurmd did not start"
    local state=""
    while ((SECONDS < deadline)); do
        live_pid "$RUN/slurmctld.pid" slurmctld >/dev/null || {
            sleep 0.2
            live_pid "$RUN/slurmctld.pid" slurmctld >/dev/null || fail "slurmctld exited"
        }
        state=$(timeout 10 sinfo -h -n "$HOST" -o %t 2>/dev/null || true)
        [[ $state == idle ]] && break
        sleep 0.2
    done
    [[ $state == idle ]] ||
        fail "node $HOST not idle after ${SOLSIM_SLURM_START_TIMEOUT:-60} s (sinfo says '${state:-nothing}')"
    live_pid "$RUN/slurmd.pid" slurmd >/dev/null || fail "slurmd is not running"
    echo "export SLURM_CONF=$CONF" >"$S/env"
    log "cluster up: node $HOST idle, ports $port/$((port + 1)), logs in $LOGS"
    echo "export SLURM_CONF=$CONF"
}

stop() {
    export SLURM_CONF=$CONF
    if live_pid "$RUN/slurmctld.pid" slurmctld >/dev/null && [[ -f $CONF ]]; then
        # Jobs still queued or running would outlive slurmd (proctrack/linuxproc): cancel them.
        local jobs i
        jobs=$(timeout 10 squeue -h -o %A 2>/dev/null | sort -u | tr '\n' ' ' || true)
        if [[ -n ${jobs// /} ]]; then
            log "cancelling jobs $jobs"
            # shellcheck disable=SC2086
            timeout 10 scancel $jobs 2>/dev/null || true
            for ((i = 0; i < 100; i++)); do
                [[ -z $(timeout 10 squeue -h -o %A 2>/dev/null || true) ]] && break
                sleep 0.1
            done
        fi
    fi
    stop_pid "$RUN/slurmd.pid" slurmd
    stop_pid "$RUN/slurmctld.pid" slurmctld
    rm -f "$RUN/slurmd.pid" "$RUN/slurmctld.pid"
    if [[ -s $S/munged.started-by-us ]]; then
        stop_pid "$S/munged.started-by-us" munged
        rm -f "$S/munged.started-by-us"
    fi
    return 0
}

status() {
    local name pid rc=0
    for name in slurmctld slurmd; do
        if pid=$(live_pid "$RUN/$name.pid" "$name"); then
            echo "$name running (pid $pid)"
        else
            echo "$name not running"
            rc=1
        fi
    done
    if munge_answers; then
        if [[ -s $S/munged.started-by-us ]]; then
            echo "munged running (started by this cluster, pid $(<"$S/munged.started-by-us"))"
        else
            echo "munged running (not started by this cluster)"
        fi
    else
        echo "munged not answering"
        rc=1
    fi
    if [[ $rc -eq 0 ]]; then
        export SLURM_CONF=$CONF
        echo "SLURM_CONF=$CONF"
        timeout 10 sinfo || rc=1
        timeout 10 squeue || rc=1
    fi
    return $rc
}

case $cmd in
start) start ;;
stop) stop ;;
status) status ;;
*) usage ;;
esac
