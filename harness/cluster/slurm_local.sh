#!/bin/sh
# A one-node Slurm cluster on this machine, from Debian's munge and slurm-wlm packages, for trying
# the job-array recipe (harness/cluster/slurm_array.sbatch) and for tests/cluster: everything
# (munge key and socket, the generated slurm.conf, state, logs, pid files) lives in DIR, nothing in
# /etc is touched, and the ports are free ones picked at start, so it sits beside a real install.
#
#   harness/cluster/slurm_local.sh start DIR   starts munged, slurmctld and slurmd; waits until the
#                                               node is idle; prints `export SLURM_CONF=DIR/slurm.conf`
#   harness/cluster/slurm_local.sh stop DIR    stops the three daemons it started (by their pid files)
#
# slurmd runs jobs as the submitting user, so `start` needs root (as slurmd does on any cluster).
# Exit status: 0 started, 1 usage, 3 the daemons could not start here (the reason printed; the
# tests skip on it).
set -u
cmd=${1:-}
dir=${2:-}
if [ -z "$cmd" ] || [ -z "$dir" ]; then
    echo "usage: $0 start|stop DIR" >&2
    exit 1
fi

stop_pidfile() {
    [ -f "$1" ] || return 0
    pid=$(cat "$1" 2>/dev/null)
    if [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; then
        kill "$pid" 2>/dev/null
        i=0
        while kill -0 "$pid" 2>/dev/null && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
        kill -0 "$pid" 2>/dev/null && kill -9 "$pid" 2>/dev/null
    fi
    rm -f "$1"
}

if [ "$cmd" = stop ]; then
    stop_pidfile "$dir/slurmd.pid"
    stop_pidfile "$dir/slurmctld.pid"
    stop_pidfile "$dir/munged.pid"
    exit 0
fi
[ "$cmd" = start ] || { echo "usage: $0 start|stop DIR" >&2; exit 1; }

cannot() {
    echo "slurm_local: cannot start a local Slurm cluster here: $*" >&2
    "$0" stop "$dir" 2>/dev/null
    exit 3
}

for b in munged mungekey slurmctld slurmd sinfo; do
    command -v "$b" >/dev/null 2>&1 || [ -x "/usr/sbin/$b" ] ||
        cannot "$b is not installed (Debian packages munge and slurm-wlm: make deps)"
done
PATH=$PATH:/usr/sbin
[ "$(id -u)" = 0 ] || cannot "slurmd must run as root to start jobs as their users (run as root, or use a real cluster)"

mkdir -p "$dir/state" "$dir/spool" "$dir/log" || cannot "cannot create $dir"
dir=$(cd "$dir" && pwd)
chmod 0700 "$dir"
if [ ${#dir} -gt 90 ]; then
    echo "slurm_local: $dir is too long a path for munge's Unix socket (108 bytes): use a shorter DIR" >&2
    exit 1
fi

# munge: a fresh key and a private socket (slurm.conf's AuthInfo points Slurm at it).
rm -f "$dir/munge.key"
mungekey --create --keyfile="$dir/munge.key" >/dev/null 2>&1 ||
    dd if=/dev/urandom of="$dir/munge.key" bs=1024 count=1 2>/dev/null
chmod 0600 "$dir/munge.key"
munged --force --key-file="$dir/munge.key" --socket="$dir/munge.socket" \
    --pid-file="$dir/munged.pid" --log-file="$dir/log/munged.log" --seed-file="$dir/munge.seed" \
    >"$dir/log/munged.out" 2>&1 || cannot "munged failed: $(tail -n 3 "$dir/log/munged.out" "$dir/log/munged.log" 2>/dev/null | tr '\n' ' ')"

# Two free TCP ports for slurmctld and slurmd.
ports=$(python3 -c 'import socket
s=[socket.socket() for _ in range(2)]
[x.bind(("127.0.0.1",0)) for x in s]
print(" ".join(str(x.getsockname()[1]) for x in s))') || cannot "no free TCP port"
set -- $ports
ctld_port=$1
d_port=$2
host=$(hostname -s)
cpus=$(nproc)
mem=$(awk '/MemTotal/ {print int($2 / 1024 / 2)}' /proc/meminfo)

# The generated slurm.conf: one node, one partition, no cgroups (a container may not delegate
# them), no accounting; jobs are tracked by process tree (proctrack/linuxproc).
cat >"$dir/slurm.conf" <<EOF
ClusterName=gibench-local
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool/%n
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
MinJobAge=300
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP OverSubscribe=YES
EOF
# slurmd reads cgroup.conf only for cgroup plugins; an empty one keeps 22.05 quiet.
: >"$dir/cgroup.conf"
export SLURM_CONF="$dir/slurm.conf"

slurmctld -i -f "$SLURM_CONF" >"$dir/log/slurmctld.out" 2>&1 ||
    cannot "slurmctld failed: $(tail -n 3 "$dir/log/slurmctld.log" "$dir/log/slurmctld.out" 2>/dev/null | tr '\n' ' ')"
slurmd -f "$SLURM_CONF" >"$dir/log/slurmd.out" 2>&1 ||
    cannot "slurmd failed: $(tail -n 3 "$dir/log/slurmd.log" "$dir/log/slurmd.out" 2>/dev/null | tr '\n' ' ')"

# Ready when the node is idle (slurmd registered with slurmctld): up to 30 s.
i=0
while [ $i -lt 60 ]; do
    state=$(sinfo -h -N -o %T 2>/dev/null | head -n 1)
    case "$state" in
    idle*) echo "export SLURM_CONF=$SLURM_CONF"; exit 0 ;;
    esac
    sleep 0.5
    i=$((i + 1))
done
cannot "the node did not become idle in 30 s (state '${state:-none}'): $(tail -n 3 "$dir/log/slurmd.log" 2>/dev/null | tr '\n' ' ')"
