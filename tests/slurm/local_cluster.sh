# shellcheck shell=bash
# Private single-node Slurm cluster for integration tests.
#
# Source this file, then:
#   slurm_cluster_install            # apt-get slurm-wlm + munge if missing
#   slurm_cluster_up   DIR           # munged + slurmctld + slurmd, all state in DIR
#   slurm_wait_jobs    JOBID...      # wait, then require every job to be COMPLETED
#   slurm_cluster_down DIR           # stop everything, remove DIR (idempotent)
#
# The cluster shares nothing with a system Slurm/munge that may be running on
# the same machine: own munge socket and key, own ports, own state, and
# SLURM_CONF (exported by slurm_cluster_up) points the client tools at it.
# Needs root (SlurmUser=root; munged and slurmd run as root).
#
# Call slurm_cluster_down from an EXIT trap: if slurm_cluster_up fails it
# prints the log tails and leaves DIR (with the logs) and any daemon it
# started for slurm_cluster_down to remove.  Down also kills processes whose
# environment has SLURM_CONF=DIR/slurm.conf (job processes), except the
# calling shell and its ancestors.

# Set by slurm_cluster_up; also used by the client commands.
SLURM_CLUSTER_DIR=${SLURM_CLUSTER_DIR:-}
SLURM_CLUSTER_NODE=${SLURM_CLUSTER_NODE:-}
# Bounds, overridable by the caller.
: "${SLURM_CLUSTER_UP_TIMEOUT:=60}"
: "${SLURM_WAIT_TIMEOUT:=120}"

_slurm_log() { echo "[local_cluster] $*" >&2; }

# ---------------------------------------------------------------- install ---

# No pipes here or below where a reader may stop early: callers often run
# with pipefail, and a writer killed by SIGPIPE would fail the pipeline.
_slurm_missing_packages() {
    local p
    for p in slurm-wlm munge; do
        [ "$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null)" = "install ok installed" ] \
            || echo "$p"
    done
}

# PIDs of the system-wide daemons, to spot ones a postinst script started.
_slurm_daemon_pids() {
    local p
    for p in /proc/[0-9]*; do
        case "$(readlink "$p/exe" 2>/dev/null)" in
            /usr/sbin/munged|/usr/sbin/slurmctld|/usr/sbin/slurmd) echo "${p#/proc/}" ;;
        esac
    done
}

slurm_cluster_install() {
    local missing=()
    mapfile -t missing < <(_slurm_missing_packages)
    [ "${#missing[@]}" -eq 0 ] && return 0
    _slurm_log "installing: ${missing[*]}"

    # Without systemd the postinst scripts still run the SysV init scripts,
    # which would start munged/slurmd on the default /etc config.  A
    # policy-rc.d answering 101 forbids that; respect one that already exists
    # (Docker images ship one) and remove only the one we create.
    local policy=/usr/sbin/policy-rc.d own_policy="" before=() rc=0 log
    if [ ! -e "$policy" ]; then
        printf '#!/bin/sh\nexit 101\n' >"$policy" && chmod 755 "$policy" && own_policy=1
    fi
    mapfile -t before < <(_slurm_daemon_pids)
    log=$(mktemp)

    DEBIAN_FRONTEND=noninteractive apt-get update -q >>"$log" 2>&1 \
        && DEBIAN_FRONTEND=noninteractive apt-get install -y -q \
               --no-install-recommends "${missing[@]}" >>"$log" 2>&1 \
        || rc=$?

    if [ -n "$own_policy" ]; then rm -f "$policy"; fi
    _slurm_stop_new_daemons "${before[@]}"

    if [ "$rc" -ne 0 ]; then
        tail -n 30 "$log" >&2
        rm -f "$log"
        _slurm_log "ERROR: apt-get failed (exit $rc) installing: ${missing[*]}"
        return 1
    fi
    rm -f "$log"
    if [ -n "$(_slurm_missing_packages)" ]; then
        _slurm_log "ERROR: still not installed after apt-get: $(_slurm_missing_packages | tr '\n' ' ')"
        return 1
    fi
}

# Kill system daemons that appeared during the install (a pre-existing
# policy-rc.d may allow starts); the PIDs given, already running before, are
# not ours to stop.
_slurm_stop_new_daemons() {
    local known=" $* " pid new=()
    for pid in $(_slurm_daemon_pids); do
        case "$known" in *" $pid "*) continue ;; esac
        _slurm_log "stopping $(readlink /proc/"$pid"/exe) (pid $pid) started by a postinst script"
        new+=("$pid")
    done
    _slurm_terminate 10 "${new[@]}"
}

# --------------------------------------------------------------------- up ---

# True if any TCP socket (listening or connected, v4 or v6) uses local PORT.
_slurm_port_in_use() {
    local hex
    hex=$(printf '%04X' "$1")
    awk -v p=":$hex" 'NR > 1 && substr($2, length($2) - 4) == p { f = 1 } END { exit !f }' \
        /proc/net/tcp /proc/net/tcp6 2>/dev/null
}

# A free port below the usual ephemeral range (32768+), so outgoing
# connections cannot grab it between now and the daemon's bind().  Never
# 6817/6818: a system Slurm may be running on the machine.
_slurm_free_port() {
    local port tries
    for ((tries = 0; tries < 200; tries++)); do
        port=$((20000 + RANDOM % 12000))
        case " $* " in *" $port "*) continue ;; esac
        _slurm_port_in_use "$port" || { echo "$port"; return 0; }
    done
    _slurm_log "ERROR: found no free TCP port"
    return 1
}

# The node's hardware line, from slurmd itself so slurmd agrees with it
# (a mismatch drains the node); without its NodeName/UpTime parts.
# RealMemory is left out: memory is not scheduled (cons_tres with CR_Core),
# and a container's view of it may change between calls.
_slurm_node_hw() {
    local hw
    hw=$(slurmd -C 2>/dev/null \
        | sed -n '/^NodeName=/{s/^NodeName=[^ ]* //; s/ *RealMemory=[0-9]*//; p}') || true
    echo "${hw:-CPUs=$(nproc)}"
}

_slurm_start_munged() {
    local dir=$1
    mkdir -p "$dir/munge"
    # munged refuses a key directory that others can write to; others must
    # be able to reach the socket, though.
    chmod 0755 "$dir/munge"
    if command -v mungekey >/dev/null; then
        mungekey --create --keyfile="$dir/munge/munge.key" || return 1
    else
        dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none || return 1
    fi
    chmod 0400 "$dir/munge/munge.key"
    # --force turns munged's checks of every directory on the key, socket
    # and log paths (no group/world-writable parent without sticky bit, socket
    # directory reachable by all) from fatal errors into warnings, so DIR can
    # live anywhere the caller likes.
    munged --force \
        --socket="$dir/munge/munge.socket" \
        --key-file="$dir/munge/munge.key" \
        --pid-file="$dir/munge/munged.pid" \
        --log-file="$dir/log/munged.log" \
        --seed-file="$dir/munge/munged.seed" \
        </dev/null >>"$dir/log/munged.out" 2>&1 || return 1
    # A credential round trip proves the daemon and key work.
    local tries
    for ((tries = 0; tries < 50; tries++)); do
        munge -n -S "$dir/munge/munge.socket" 2>/dev/null \
            | unmunge -S "$dir/munge/munge.socket" >/dev/null 2>&1 && return 0
        sleep 0.1
    done
    _slurm_log "ERROR: munged did not answer on $dir/munge/munge.socket"
    return 1
}

_slurm_write_conf() {
    local dir=$1 node=$2 ctld_port=$3 slurmd_port=$4 cluster
    cluster="swa$(date +%s)$$"
    cat >"$dir/slurm.conf" <<CONF
# Generated by tests/slurm/local_cluster.sh for a throw-away test cluster.
ClusterName=$cluster
# slurmctld refuses to start ("not a valid controller") unless this matches
# the machine's hostname, except for the name localhost, which it accepts
# anywhere; so the machine's hostname does not matter.
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# No systemd/cgroups in the container: track processes via /proc.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
# Keep finished jobs visible to scontrol (no slurmdbd, so no sacct).
MinJobAge=3600
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
# Debian's slurmctld complains about the default /bin/mail being absent.
MailProg=/bin/true
NodeName=$node NodeAddr=127.0.0.1 $(_slurm_node_hw) State=UNKNOWN
PartitionName=test Nodes=$node Default=YES State=UP MaxTime=INFINITE
CONF
}

slurm_cluster_up() {
    local dir=${1:?usage: slurm_cluster_up DIR}
    if [ "$(id -u)" -ne 0 ]; then
        _slurm_log "ERROR: needs root (SlurmUser=root, munged/slurmd as root)"
        return 1
    fi
    mkdir -p "$dir" || return 1
    dir=$(cd "$dir" && pwd -P) || return 1
    if [ -n "$(ls -A "$dir")" ] && [ ! -e "$dir/.swa_local_cluster" ]; then
        _slurm_log "ERROR: $dir is not empty; refusing to use it"
        return 1
    fi
    : >"$dir/.swa_local_cluster"       # lets slurm_cluster_down rm -rf it safely
    # mktemp -d makes 0700; munged warns that other users could not reach
    # its socket, and jobs run as other users could not read their files.
    chmod 0755 "$dir"
    mkdir -p "$dir/log" "$dir/run" "$dir/state" "$dir/spool"

    # slurmd -N NAME makes it that node whatever the machine's hostname is.
    local node ctld_port slurmd_port
    node="swa-node-$$"
    ctld_port=$(_slurm_free_port) || return 1
    slurmd_port=$(_slurm_free_port "$ctld_port") || return 1
    _slurm_write_conf "$dir" "$node" "$ctld_port" "$slurmd_port" || return 1

    SLURM_CLUSTER_DIR=$dir
    SLURM_CLUSTER_NODE=$node
    export SLURM_CONF="$dir/slurm.conf"

    _slurm_start_munged "$dir" || { _slurm_dump_logs "$dir"; return 1; }
    slurmctld -f "$dir/slurm.conf" \
        </dev/null >>"$dir/log/slurmctld.out" 2>&1 \
        || { _slurm_log "ERROR: slurmctld failed to start"; _slurm_dump_logs "$dir"; return 1; }
    slurmd -f "$dir/slurm.conf" -N "$node" \
        </dev/null >>"$dir/log/slurmd.out" 2>&1 \
        || { _slurm_log "ERROR: slurmd failed to start"; _slurm_dump_logs "$dir"; return 1; }

    _slurm_wait_node_idle "$dir" "$node" || { _slurm_dump_logs "$dir"; return 1; }
    _slurm_log "cluster up in $dir (node $node, ports $ctld_port/$slurmd_port)"
}

_slurm_wait_node_idle() {
    local dir=$1 node=$2 state="" deadline=$((SECONDS + SLURM_CLUSTER_UP_TIMEOUT))
    while [ "$SECONDS" -lt "$deadline" ]; do
        state=$(timeout 10 sinfo -h -N -n "$node" -o %T 2>/dev/null || true)
        [ "$state" = idle ] && return 0
        sleep 0.5
    done
    _slurm_log "ERROR: node $node not idle after ${SLURM_CLUSTER_UP_TIMEOUT}s (state: '${state:-no answer}')"
    return 1
}

_slurm_dump_logs() {
    local f
    for f in "$1"/log/*; do
        [ -s "$f" ] || continue
        echo "----- tail of $f -----" >&2
        tail -n 30 "$f" >&2
    done
}

# ------------------------------------------------------------------- jobs ---

# slurm_wait_jobs JOBID... : wait (at most SLURM_WAIT_TIMEOUT s) until the
# jobs (array jobs: all their tasks) have left the queue, print each one's
# final state, and fail unless every one of them is COMPLETED.  A job pending
# on a dependency that can never be satisfied counts as finished (and failed).
slurm_wait_jobs() {
    [ "$#" -gt 0 ] || { _slurm_log "usage: slurm_wait_jobs JOBID..."; return 2; }
    local ids queued deadline=$((SECONDS + SLURM_WAIT_TIMEOUT))
    ids=$(IFS=,; echo "$*")
    while :; do
        if queued=$(timeout 10 squeue -h -j "$ids" -o '%i %T %r' 2>/dev/null); then
            queued=$(echo "$queued" | grep -v ' PENDING DependencyNeverSatisfied$' || true)
            [ -z "$queued" ] && break
        fi
        if [ "$SECONDS" -ge "$deadline" ]; then
            _slurm_log "ERROR: jobs still queued after ${SLURM_WAIT_TIMEOUT}s:"
            echo "${queued:-(squeue not answering)}" >&2
            _slurm_job_states "$@" >&2 || true
            return 1
        fi
        sleep 0.5
    done
    _slurm_job_states "$@"
}

# One "id state reason exit-code" line per job or array task; fails if any
# state is not COMPLETED.  Finished jobs stay visible for MinJobAge seconds.
_slurm_job_states() {
    local id out rc=0
    for id in "$@"; do
        if ! out=$(timeout 10 scontrol show job -o "$id" 2>&1); then
            echo "$id UNKNOWN ($out)"
            rc=1
            continue
        fi
        echo "$out" | awk '{
            for (i = 1; i <= NF; i++) { split($i, kv, "="); f[kv[1]] = substr($i, length(kv[1]) + 2) }
            id = f["JobId"]
            if (f["ArrayTaskId"] != "") id = f["ArrayJobId"] "_" f["ArrayTaskId"]
            print id, f["JobState"], f["Reason"], f["ExitCode"]
            if (f["JobState"] != "COMPLETED") bad = 1
        } END { exit bad }' || rc=1
    done
    return "$rc"
}

# ------------------------------------------------------------------- down ---

# PIDs of processes belonging to the cluster in DIR, one a line: same uid as
# us and either a command line naming a path under DIR (daemons, batch
# scripts) or SLURM_CONF=DIR/slurm.conf in the environment, plus all their
# descendants.  slurmstepd's command line is just "slurmstepd: [1.batch]" and
# slurmd gives it a clean environment, but one with SLURM_CONF; job processes
# get it from sbatch's exported environment.  Never this shell or its
# ancestors: a caller started with SLURM_CONF=DIR/slurm.conf must survive.
_slurm_cluster_pids() {
    local dir=$1 p pid stat entry args grew
    local -A parent=() protected=() matched=()

    # `read <file` rather than `$(<file)` for /proc files: processes vanish
    # meanwhile, and bash 5.2 under set -e exits on a failed $(<file) even
    # when followed by || continue.
    pid=$BASHPID
    while [ "$pid" -gt 1 ] 2>/dev/null; do
        protected[$pid]=1
        read -r stat 2>/dev/null <"/proc/$pid/stat" || break
        stat=${stat##*) }; stat=${stat#* }; pid=${stat%% *}
    done

    for p in /proc/[0-9]*; do
        pid=${p#/proc/}
        [ -O "$p" ] || continue
        read -r stat 2>/dev/null <"$p/stat" || continue
        stat=${stat##*) }; stat=${stat#* }; parent[$pid]=${stat%% *}
        [ -z "${protected[$pid]:-}" ] || continue
        args=()
        mapfile -d '' args 2>/dev/null <"$p/cmdline" || continue
        case "${args[*]}" in *"$dir/"*) matched[$pid]=1; continue ;; esac
        while IFS= read -r -d '' entry; do
            if [ "$entry" = "SLURM_CONF=$dir/slurm.conf" ]; then
                matched[$pid]=1
                break
            fi
        done 2>/dev/null <"$p/environ" || true
    done

    # Close over descendants (several passes: /proc order is not tree order).
    grew=1
    while [ -n "$grew" ]; do
        grew=""
        for pid in "${!parent[@]}"; do
            [ -z "${matched[$pid]:-}" ] && [ -z "${protected[$pid]:-}" ] \
                && [ -n "${matched[${parent[$pid]}]:-}" ] \
                && { matched[$pid]=1; grew=1; }
        done
    done
    [ "${#matched[@]}" -eq 0 ] || printf '%s\n' "${!matched[@]}"
}

# True while any PID runs.  Zombies count as gone: daemons are reparented to
# PID 1, which may reap them late, and kill -0 still succeeds on a zombie.
_slurm_alive() {
    local pid stat
    for pid in "$@"; do
        read -r stat 2>/dev/null <"/proc/$pid/stat" || continue
        stat=${stat##*) }
        [ "${stat%% *}" != Z ] && return 0
    done
    return 1
}

# TERM, then KILL whatever is still there after WAIT seconds.
_slurm_terminate() {
    local wait=$1 deadline; shift
    [ "$#" -gt 0 ] || return 0
    kill -TERM "$@" 2>/dev/null || true
    deadline=$((SECONDS + wait))
    while _slurm_alive "$@" && [ "$SECONDS" -lt "$deadline" ]; do sleep 0.2; done
    if _slurm_alive "$@"; then
        _slurm_log "still running after ${wait}s, sending KILL: $*"
        kill -KILL "$@" 2>/dev/null || true
        sleep 0.2
    fi
}

# PID from a pid file, only if that process still names DIR on its command
# line (guards against a recycled PID).
_slurm_pidfile_pid() {
    local file=$1 dir=$2 pid args=()
    pid=$(cat "$file" 2>/dev/null) || return 0
    [[ $pid =~ ^[0-9]+$ ]] || return 0
    mapfile -d '' args 2>/dev/null <"/proc/$pid/cmdline" || return 0
    case "${args[*]}" in *"$dir/"*) echo "$pid" ;; esac
}

# Cancel the jobs first so slurmstepd ends the job processes itself
# (TERM, then KILL after KillWait); they show as COMPLETING until then.
_slurm_cancel_all_jobs() {
    local dir=$1 deadline
    [ -n "$(_slurm_pidfile_pid "$dir/run/slurmctld.pid" "$dir")" ] || return 0
    SLURM_CONF=$dir/slurm.conf timeout 10 scancel --user="$(id -un)" 2>/dev/null || return 0
    deadline=$((SECONDS + 15))
    while [ "$SECONDS" -lt "$deadline" ]; do
        [ -z "$(SLURM_CONF=$dir/slurm.conf timeout 10 squeue -h -o %i 2>/dev/null)" ] && return 0
        sleep 0.3
    done
}

slurm_cluster_down() {
    local dir=${1:-$SLURM_CLUSTER_DIR}
    [ -n "$dir" ] || return 0
    [ -d "$dir" ] && dir=$(cd "$dir" && pwd -P)
    if [ -d "$dir" ] && [ ! -e "$dir/.swa_local_cluster" ]; then
        _slurm_log "ERROR: $dir was not made by slurm_cluster_up; not touching it"
        return 1
    fi

    local pids=()
    if [ -d "$dir" ]; then
        _slurm_cancel_all_jobs "$dir"
        # munged last: the Slurm daemons still authenticate while stopping.
        mapfile -t pids < <(_slurm_pidfile_pid "$dir/run/slurmd.pid" "$dir"
                            _slurm_pidfile_pid "$dir/run/slurmctld.pid" "$dir")
        _slurm_terminate 10 "${pids[@]}"
        mapfile -t pids < <(_slurm_pidfile_pid "$dir/munge/munged.pid" "$dir")
        _slurm_terminate 10 "${pids[@]}"
    fi
    # Anything left: orphaned job processes, slurmstepd, daemons whose pid
    # file was lost.  Also runs when DIR is already gone (second call).
    mapfile -t pids < <(_slurm_cluster_pids "$dir")
    _slurm_terminate 5 "${pids[@]}"

    rm -rf "$dir"
    if [ "${SLURM_CONF:-}" = "$dir/slurm.conf" ]; then unset SLURM_CONF; fi
    if [ "$SLURM_CLUSTER_DIR" = "$dir" ]; then SLURM_CLUSTER_DIR=""; SLURM_CLUSTER_NODE=""; fi
    return 0
}
