#!/bin/sh
# A one-box Slurm for trying the sweeps' Slurm runners (docs/ballistic_limit.md "Runners")
# and for tests/sh/slurm_sweep.sh: munge and Slurm started by hand, no systemd, every
# file under one folder, this host its one node.
#
# Usage (as root; Debian's slurm-wlm and munge: make deps):
#   sh tools/slurm_box.sh start DIR [CPUS]   start munged, slurmctld and slurmd with their
#                                             files in DIR (made; CPUS: the node's CPUs, the
#                                             machine's by default); prints the line
#                                             "export SLURM_CONF=DIR/slurm.conf" for the clients
#   sh tools/slurm_box.sh stop DIR            stop the three daemons started in DIR
# Ports: SlurmctldPort and SlurmdPort are picked from the process id (two boxes on one
# machine do not collide). Exit codes: 0 up (the node idle) or stopped; 1 it did not come
# up (the reason, and the daemons' logs in DIR); 2 a bad call; 3 it cannot start here
# (not root, or a program missing): one line says why.
set -u
what=${1:-} dir=${2:-}
[ -n "$what" ] && [ -n "$dir" ] || { echo "usage: sh tools/slurm_box.sh start|stop DIR [CPUS]"; exit 2; }
case "$dir" in /*) ;; *) dir="$(pwd)/$dir" ;; esac

stop() {
    for f in slurmd slurmctld munged; do
        [ -s "$dir/$f.pid" ] || continue
        pid=$(cat "$dir/$f.pid")
        case "$pid" in ''|*[!0-9]*) continue ;; esac
        kill "$pid" 2>/dev/null
        for _ in 1 2 3 4 5 6 7 8 9 10; do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
        kill -9 "$pid" 2>/dev/null
        rm -f "$dir/$f.pid"
    done
    return 0
}
if [ "$what" = stop ]; then stop; exit 0; fi
[ "$what" = start ] || { echo "usage: sh tools/slurm_box.sh start|stop DIR [CPUS]"; exit 2; }
cpus=${3:-$(nproc 2>/dev/null || echo 1)}
case "$cpus" in ''|*[!0-9]*|0) echo "slurm_box: CPUS '$cpus' is not a count"; exit 2 ;; esac
[ "$(id -u)" -eq 0 ] || { echo "slurm_box: cannot start: not root (slurmd starts jobs as their users)"; exit 3; }
for p in munged mungekey slurmctld slurmd srun sbatch squeue scontrol; do
    command -v "$p" >/dev/null 2>&1 || [ -x "/usr/sbin/$p" ] ||
        { echo "slurm_box: cannot start: no $p (Debian's slurm-wlm and munge: make deps)"; exit 3; }
done
PATH="$PATH:/usr/sbin"
mkdir -p "$dir/munge" "$dir/state" "$dir/spool" || { echo "slurm_box: cannot make $dir"; exit 1; }
chmod 700 "$dir/munge"
host=$(hostname -s 2>/dev/null || hostname)
base=$(( 20000 + ($$ % 2000) * 2 ))
# munge: a key of our own, a socket in DIR (Slurm's AuthInfo names it)
rm -f "$dir/munge/munge.key"
mungekey -c -k "$dir/munge/munge.key" > "$dir/munge/mungekey.log" 2>&1 ||
    dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 2>/dev/null
chmod 400 "$dir/munge/munge.key"
munged -f --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
    --pid-file="$dir/munged.pid" --log-file="$dir/munge/munged.log" \
    --seed-file="$dir/munge/munged.seed" > "$dir/munge/start.log" 2>&1 ||
    { echo "slurm_box: munged did not start: $(tail -1 "$dir/munge/start.log")"; stop; exit 1; }
cat > "$dir/slurm.conf" <<EOF
# a one-box Slurm (tools/slurm_box.sh)
ClusterName=wovenff
SlurmctldHost=$host
SlurmctldPort=$base
SlurmdPort=$((base + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
ReturnToService=2
SchedulerParameters=sched_interval=1
MinJobAge=4
KillWait=2
# (sbatch --wait checks a job at 2 s, then x4 up to 32 s while below MinJobAge/2: 4 keeps it at 2 s)
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=box Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -f "$dir/slurm.conf" > "$dir/slurmctld.start.log" 2>&1 ||
    { echo "slurm_box: slurmctld did not start: $(tail -1 "$dir/slurmctld.start.log")"; stop; exit 1; }
slurmd -f "$dir/slurm.conf" > "$dir/slurmd.start.log" 2>&1 ||
    { echo "slurm_box: slurmd did not start: $(tail -1 "$dir/slurmd.start.log")"; stop; exit 1; }
SLURM_CONF="$dir/slurm.conf"; export SLURM_CONF
for _ in $(seq 1 50); do
    state=$(sinfo -h -o %T 2>/dev/null | head -1)
    case "$state" in idle*) echo "export SLURM_CONF=$dir/slurm.conf"; exit 0 ;; esac
    sleep 0.2
done
echo "slurm_box: the node did not come up in 10 s (state '${state:-}'; $dir/slurmctld.log, $dir/slurmd.log)"
stop
exit 1
