#!/bin/sh
# Run a FreeFEM script with wovenff's module and .idp library on the paths.
# Usage: tools/ff.sh script.edp [script arguments...]
# Run from the repository root (the Makefile does).
root=$(cd "$(dirname "$0")/.." && pwd)
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
exec FreeFem++ -nw -v 0 "$script" "$@"
