#!/bin/sh
# Run a FreeFEM script with wovenff's module and .idp library on the paths.
# Usage: tools/ff.sh [-np N] script.edp [script arguments...]
#   -np N: one model over N MPI ranks (docs/distributed.md): mpirun -np N FreeFem++-mpi with
#          the MPI module (build/mpi/wovenff.so: make builds it where OpenMPI's mpicc is);
#          rank 0 prints and writes the results, the other ranks' output goes nowhere;
#          the ranks run on this machine (a cluster: mpirun yourself, README "How to run on a
#          cluster"); WFF_MPIRUN_ARGS: more of mpirun's options (--bind-to none for -threads > 1).
# Run from the repository root (the Makefile does).
root=$(cd "$(dirname "$0")/.." && pwd)
if [ "${1:-}" = "-np" ]; then
    np=$2; shift 2
    case "$np" in ''|*[!0-9]*|0) echo "tools/ff.sh: -np needs a rank count >= 1, not '$np'" >&2; exit 2 ;; esac
    if [ ! -f "$root/build/mpi/wovenff.so" ]; then
        echo "tools/ff.sh: -np $np needs the MPI module build/mpi/wovenff.so: make deps (OpenMPI), then make" >&2
        exit 2
    fi
    FF_LOADPATH="$root/build/mpi;/usr/lib/freefem++"
    FF_INCLUDEPATH="$root/freefem_scripts/lib;$root/freefem_scripts;/usr/include/freefem++/idp"
    OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-PASSIVE}
    # a private temporary folder for the ranks' scratch (wovenffRankDir), removed after the run
    scratch=$(mktemp -d "${TMPDIR:-/tmp}/wovenff-mpi-XXXXXX") || exit 2
    TMPDIR=$scratch
    export FF_LOADPATH FF_INCLUDEPATH OMP_WAIT_POLICY TMPDIR
    # OpenMPI refuses root unless told; more ranks than cores needs --oversubscribe
    if [ "$(id -u)" -eq 0 ]; then
        OMPI_ALLOW_RUN_AS_ROOT=1; OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
        export OMPI_ALLOW_RUN_AS_ROOT OMPI_ALLOW_RUN_AS_ROOT_CONFIRM
    fi
    over=""; [ "$np" -gt "$(nproc)" ] && over=--oversubscribe
    # (--mca plm isolated: the ranks on this machine, also inside a Slurm job step, where
    # mpirun would otherwise ask Slurm to start its daemons)
    # shellcheck disable=SC2086 # ($over and $WFF_MPIRUN_ARGS: words for mpirun, e.g. --bind-to none)
    mpirun --mca plm isolated -np "$np" $over ${WFF_MPIRUN_ARGS:-} -x FF_LOADPATH -x FF_INCLUDEPATH -x OMP_WAIT_POLICY -x TMPDIR \
        sh -c 'if [ "${OMPI_COMM_WORLD_RANK:-0}" != 0 ]; then exec >/dev/null; fi; exec FreeFem++-mpi -nw -v 0 "$@"' sh "$@"
    rc=$?
    rm -rf "$scratch"
    exit "$rc"
fi
FF_LOADPATH="$root/build;/usr/lib/freefem++"
FF_INCLUDEPATH="$root/freefem_scripts/lib;$root/freefem_scripts;/usr/include/freefem++/idp"
export FF_LOADPATH FF_INCLUDEPATH
# OpenMP threads that wait at a barrier sleep instead of spinning (unless the
# caller chose a policy or a spin count): on a shared machine a spinning thread
# burns the time slice its partner needs. The paper's scene, 2 threads: idle
# machine 0.41 s spinning (GOMP_SPINCOUNT=20000) vs 0.65 s passive, but with one
# busy process beside it 3.0 s vs 0.51 s, two scenes at once 7.0 s vs 0.51 s
# each (docs/limits.md "Threads"); OMP_WAIT_POLICY=active on a machine of your own.
if [ -z "${OMP_WAIT_POLICY:-}" ] && [ -z "${GOMP_SPINCOUNT:-}" ]; then
    OMP_WAIT_POLICY=PASSIVE
    export OMP_WAIT_POLICY
fi
script=$1; shift
# On a terminal, FreeFEM's trailer after a scene's own exit ("  current line = N", " call F  at
# line N", "exit(N)", " err code N ,  mpirank 0": FreeFEM prints it at every exit, -help and a
# refused option included) is left out of what the user sees, the exit code kept; after an
# uncaught error (exit 8 or any code the scenes do not give: docs/limits.md "Exit codes") the
# trailer is shown, it says where. Elsewhere (a file, a pipe, the tests) the output is FreeFEM's
# own and this script becomes FreeFEM (exec: the same process id).
if [ -t 1 ] && [ -z "${WOVENFF_TRAILER:-}" ]; then
    exec 4>&1
    rc=$( { { FreeFem++ -nw -v 0 "$script" "$@" 2>&1; echo $? >&3; } |
            awk '/^  current line = [0-9]+$/ || /^ call .* at  line [0-9]+$/ || /^exit\([0-9]+\)$/ {
                     held = held $0 "\n"; next }
                 /^ err code [0-9]+ ,  mpirank [0-9]+$/ {
                     code = $3 + 0
                     if (code != 0 && code != 2 && code != 3 && code != 4 && code != 5 && code != 6 && code != 7 && code != 9)
                         printf "%s%s\n", held, $0
                     held = ""; fflush(); next }
                 { if (held != "") { printf "%s", held; held = "" } print; fflush() }
                 END { printf "%s", held }' >&4; } 3>&1 )
    exit "$rc"
fi
exec FreeFem++ -nw -v 0 "$script" "$@"
