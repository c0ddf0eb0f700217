#!/bin/sh
# The sweeps' runners (issue 28, item 5; docs/ballistic_limit.md "Runners"):
#  - without Slurm: -runner srun outside an allocation, -ranks 2 without FreeFem++-mpi on
#    PATH, -resume 1 with -overwrite 1 stop with exit 2 naming what is wrong; -ranks 2 runs
#    each run as `sh tools/ff.sh -np 2 SCENE ...`, an mpirun of FreeFem++-mpi with the MPI
#    module (an mpirun stand-in on PATH logs its arguments and runs the scene on one
#    process), a value with a blank reaching the run as one argument; an interrupted
#    sweep (its last runs removed) taken up again with -resume 1 runs only those and
#    gives the same limit.csv;
#  - on a one-box Slurm this test starts itself (tools/slurm_box.sh: munged, slurmctld,
#    slurmd by hand, every file under the test's folder, stopped at the end even on
#    failure): the ballistic-limit sweep (the stand-in scene of tests/sh/limit_scene.sh)
#    through -runner srun inside `sbatch -n 2 --wait` gives the same runs and V50 as
#    -runner local, each run a job step; the sensitivity study (coarse mesh, 3 runs) as a
#    job array with one task cancelled while it runs: reported killed with its log, which
#    holds Slurm's words; -resume 1 runs that one alone and the study's sensitivity.csv is
#    the local runner's, byte for byte.
# Where Slurm cannot start (not root, slurm-wlm or munge missing) it says so in one line
# and passes. Every Slurm call has a timeout.
# test-runner: first (~24 s: one of the longest tests; tests/run.sh starts the longest first)
set -u
tmp="${WFF_TEST_TMP:-/tmp}/slurm_sweep"
rm -rf "$tmp"; mkdir -p "$tmp/bin"
fail=0
standin=tests/edp/scenes/lambert_jonas_standin.edp
law="-law 120,0.9,2.5"
limit() { # out, options...: the stand-in sweep
    out=$1; shift
    timeout -k 5 120 sh tools/ff.sh freefem_scripts/ballistic_limit.edp -scene $standin -out "$tmp/$out" -plots 0 \
        -vmin 100 -vmax 300 -runs 8 "$@" > "$tmp/$out.log" 2>&1
}
v50() { sed -n 's/^V50 \(.*\)$/\1/p' "$tmp/$1.log"; }
runs() { cut -d, -f1-5 "$tmp/$1/limit.csv"; }   # (striking, residual, perforated, status, round)

# 1. refusals, exit 2
limit nosrun -base "$law" -runner srun
rc=$?
[ $rc -eq 2 ] && grep -q '^error: ballistic_limit: -runner srun: .*not inside a Slurm allocation (SLURM_JOB_ID is not set)' "$tmp/nosrun.log" \
    || { echo "-runner srun outside an allocation: exit $rc"; tail -3 "$tmp/nosrun.log"; fail=1; }
for p in FreeFem++ dirname sh timeout; do ln -s "$(command -v $p)" "$tmp/bin/$p"; done
(PATH="$tmp/bin"; limit nompi -base "$law" -ranks 2)
rc=$?
[ $rc -eq 2 ] && grep -q '^error: ballistic_limit: -ranks 2: .*needs FreeFEM.s MPI build, and FreeFem++-mpi is not on PATH' "$tmp/nompi.log" \
    || { echo "-ranks 2 without FreeFem++-mpi: exit $rc"; tail -3 "$tmp/nompi.log"; fail=1; }
[ -e "$tmp/nompi" ] && { echo "-ranks 2 refused, yet $tmp/nompi was made"; fail=1; }
limit both -base "$law" -resume 1 -overwrite 1
rc=$?
[ $rc -eq 2 ] && grep -q '^error: ballistic_limit: -resume 1 .* -overwrite 1 .*not both' "$tmp/both.log" \
    || { echo "-resume 1 -overwrite 1: exit $rc"; tail -3 "$tmp/both.log"; fail=1; }

# 2. -ranks 2: the launch (an mpirun stand-in logs its arguments, runs the rest on one process)
rm -f "$tmp/bin/"*
cat > "$tmp/bin/mpirun" <<'EOF'
#!/bin/sh
line=$(printf '%s|' "$@"); printf '%s\n' "$line" >> "$WFF_MPIRUN_CALLS"   # (one write: jobs run at once)
while [ $# -gt 0 ] && [ "$1" != sh ]; do shift; done
exec "$@"
EOF
chmod +x "$tmp/bin/mpirun"
limit local -base "$law" -mesh "a b" -jobs 2
rcl=$?
[ $rcl -eq 0 ] || { echo "the local sweep: exit $rcl"; tail -3 "$tmp/local.log"; fail=1; }
if [ ! -f build/mpi/wovenff.so ]; then
    echo "SKIP -ranks 2: no MPI module build/mpi/wovenff.so (OpenMPI's libopenmpi-dev: make deps)"
else
(PATH="$tmp/bin:$PATH"; WFF_MPIRUN_CALLS="$tmp/mpirun.calls"; export WFF_MPIRUN_CALLS
 limit ranks -base "$law" -mesh "a b" -jobs 2 -ranks 2)
rc=$?
[ $rc -eq 0 ] || { echo "-ranks 2 sweep exit $rc"; tail -3 "$tmp/ranks.log"; fail=1; }
n=$(grep -c "^--mca|plm|isolated|-np|2|.*-x|FF_LOADPATH|.*|sh|-c|[^|]*exec FreeFem++-mpi -nw -v 0 [^|]*|sh|$standin|.*|-mesh|a b|.*-velocity|[0-9.]*|-out|$tmp/ranks/v[0-9.]*|\$" "$tmp/mpirun.calls" 2>/dev/null)
[ "$n" = 8 ] || { echo "-ranks 2: $n of 8 runs launched as mpirun -np 2 ... FreeFem++-mpi with '-mesh' 'a b'"; head -2 "$tmp/mpirun.calls"; fail=1; }
[ "$(runs ranks)" = "$(runs local)" ] && [ -n "$(v50 local)" ] && [ "$(v50 ranks)" = "$(v50 local)" ] \
    || { echo "-ranks 2: V50 '$(v50 ranks)', local '$(v50 local)'"; fail=1; }
fi

# 3. -resume 1: a sweep cut short (its last two runs gone) taken up again
cp -r "$tmp/local" "$tmp/resumed"
sed -i "s#$tmp/local/#$tmp/resumed/#g" "$tmp/resumed/runs.txt"
last=$(awk -F, 'NR > 1 { print $5, $1 }' "$tmp/local/limit.csv" | sort -n | tail -2 | awk '{ print "v" $2 }')
for v in $last; do rm -r "${tmp:?}/resumed/$v"; done
rm -f "$tmp/resumed/limit.csv" "$tmp/resumed/limit.json"
limit resumed -base "$law" -mesh "a b" -jobs 2 -resume 1
rc=$?
ran=$(grep -c '^  \[[0-9]*/[0-9]*\] v' "$tmp/resumed.log")
[ $rc -eq 0 ] && [ "$ran" = 2 ] && [ "$(runs resumed)" = "$(runs local)" ] \
    || { echo "-resume 1: exit $rc, $ran runs run (want 2: $last), limit.csv the same: $(runs resumed | wc -l) rows"; fail=1; }
grep -q 'taken from the earlier sweep' "$tmp/resumed.log" || { echo "-resume 1: no run said taken"; fail=1; }

# 4. a one-box Slurm
box="$tmp/box"
up=$(timeout -k 5 60 sh tools/slurm_box.sh start "$box" 2)
rc=$?
if [ $rc -eq 3 ]; then
    echo "SKIP the Slurm part: $up"
    exit $fail
fi
stop_box() {
    SLURM_CONF="$box/slurm.conf" timeout 10 scancel --user "$(id -un)" 2>/dev/null
    for _ in $(seq 1 25); do
        [ -z "$(SLURM_CONF="$box/slurm.conf" timeout 5 squeue -h 2>/dev/null)" ] && break; sleep 0.2
    done
    timeout -k 5 30 sh tools/slurm_box.sh stop "$box"
}
trap stop_box EXIT
trap 'exit 1' INT TERM
[ $rc -eq 0 ] || { echo "the one-box Slurm did not come up: $up"; tail -n 3 "$box/slurmctld.log" "$box/slurmd.log"; exit 1; }
SLURM_CONF="$box/slurm.conf"; export SLURM_CONF

# 4a. the V50 sweep through job steps inside one allocation, and locally
t0=$(date +%s.%N)
timeout -k 5 120 sbatch -n 2 --wait -J limit_srun -o "$tmp/srun.out" --wrap \
    "sh tools/ff.sh freefem_scripts/ballistic_limit.edp -scene $standin -out '$tmp/srun' -plots 0 -vmin 100 -vmax 300 -runs 8 -base '$law' -mesh 'a b' -jobs 2 -runner srun" \
    > "$tmp/sbatch.log" 2>&1
rc=$?
t1=$(date +%s.%N)
cp "$tmp/srun.out" "$tmp/srun.log" 2>/dev/null
job=$(sed -n 's/^Submitted batch job \([0-9]*\)$/\1/p' "$tmp/sbatch.log")
steps=$(grep -c "launch task StepId=$job\.[0-9]" "$box/slurmd.log")
echo "V50: local $(v50 local); srun $(v50 srun) ($steps job steps of job $job, $(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }') s)"
[ $rc -eq 0 ] && [ -n "$(v50 srun)" ] && [ "$(v50 srun)" = "$(v50 local)" ] && [ "$(runs srun)" = "$(runs local)" ] \
    || { echo "-runner srun: sbatch exit $rc, V50 '$(v50 srun)' vs local '$(v50 local)'"; tail -n 5 "$tmp/srun.log" "$tmp/sbatch.log"; fail=1; }
grep -q "^runs on job steps of Slurm job $job" "$tmp/srun.log" || { echo "-runner srun: no 'runs on job steps' line"; fail=1; }
[ "$steps" = 8 ] || { echo "-runner srun: $steps job steps in job $job, want 8 (a step a run)"; fail=1; }

# 4b. the sensitivity study as a job array, one task cancelled while it runs
base="-mesh coarse -tend 1.5e-3 -threads 1"
sens() { # out, options...
    out=$1; shift
    timeout -k 5 150 sh tools/ff.sh freefem_scripts/sensitivity.edp -base "$base" -inputs velocity:18:26 -plots 0 \
        -out "$tmp/$out" "$@" > "$tmp/$out.log" 2>&1
}
sens array -runner slurm -jobs 1 &
pid=$!
task=""
for _ in $(seq 1 300); do   # (the second run's log: its task has started the scene)
    if [ -e "$tmp/array/runs/01_velocity_low.log" ]; then
        task=$(timeout 10 squeue -h -t R -o %i | grep '_1$' | head -1)
        [ -n "$task" ] && break
    fi
    kill -0 $pid 2>/dev/null || break
    sleep 0.2
done
[ -n "$task" ] && timeout 10 scancel "$task"
wait $pid
rc=$?
echo "job array: task $task cancelled; $(grep '^failed run' "$tmp/array.log")"
[ -n "$task" ] || { echo "the job array's task 1 never ran"; tail -5 "$tmp/array.log"; fail=1; }
log="$tmp/array/runs/01_velocity_low/run.log"
[ $rc -eq 0 ] && grep -q "^failed run velocity_low: killed: job array task $task ended without an exit status.* (Slurm: \*\*\* JOB [0-9]* ON .* CANCELLED AT .*) (log: $log)" "$tmp/array.log" \
    || { echo "the cancelled task is not reported killed with its log (exit $rc)"; tail -12 "$tmp/array.log"; fail=1; }
grep -q '^error: killed: job array task' "$log" && grep -q "CANCELLED" "$log" \
    || { echo "$log: no 'error: killed' line or no Slurm words"; tail -5 "$log"; fail=1; }
grep -q '"runs": 3, "runs_failed": 1' "$tmp/array/sensitivity.json" || { echo "sensitivity.json: not 3 runs, 1 failed"; fail=1; }
ls "$tmp/array/runs" | grep -q 'jobs.txt\|[.]exit$\|[.]slurm$' && { echo "the job array's files left in runs/: $(ls "$tmp/array/runs")"; fail=1; }
h0=$(md5sum < "$tmp/array/runs/00_base/summary.json")
sens array -runner slurm -jobs 1 -resume 1
rc=$?
grep '^  \[' "$tmp/array.log"
[ $rc -eq 0 ] && grep -q '^2 of 3 runs taken from the earlier study (-resume 1), 1 to run' "$tmp/array.log" \
    && grep -q '^  \[1/1\] velocity_low: ok' "$tmp/array.log" && grep -q '"runs_failed": 0' "$tmp/array/sensitivity.json" \
    || { echo "-resume 1: exit $rc"; tail -8 "$tmp/array.log"; fail=1; }
[ "$(md5sum < "$tmp/array/runs/00_base/summary.json")" = "$h0" ] || { echo "-resume 1 ran the finished base run again"; fail=1; }
sens sens_local -jobs 2
rc=$?
[ $rc -eq 0 ] && cmp -s "$tmp/sens_local/sensitivity.csv" "$tmp/array/sensitivity.csv" \
    || { echo "the job array's sensitivity.csv is not the local runner's (exit $rc)"; diff "$tmp/sens_local/sensitivity.csv" "$tmp/array/sensitivity.csv" | head -5; fail=1; }
exit $fail
