#!/bin/sh
# Run a FreeFEM script with wovenff's module and .idp library on the paths.
# Usage: tools/ff.sh script.edp [script arguments...]
# Run from the repository root (the Makefile does).
root=$(cd "$(dirname "$0")/.." && pwd)
FF_LOADPATH="$root/build;/usr/lib/freefem++"
FF_INCLUDEPATH="$root/freefem_scripts/lib;$root/freefem_scripts;/usr/include/freefem++/idp"
export FF_LOADPATH FF_INCLUDEPATH
# OpenMP threads that wait at a barrier spin a bounded while, then sleep (unless
# the caller chose a policy or a spin count): libgomp's default spin (300000
# rounds) burns, on a shared machine, the time slice the partner thread needs
# (2 threads ran 4-5x slower than 1), and sleeping at once (OMP_WAIT_POLICY=
# PASSIVE) costs a wake-up per barrier: on the paper's scene (2288 elements,
# ~30000 steps) 2 threads took 6.3-6.9 s passive, 4.3 s spinning, 4.7 s with
# this bound, 5.6 s on 1 thread (docs/limits.md "Threads")
if [ -z "${OMP_WAIT_POLICY:-}" ] && [ -z "${GOMP_SPINCOUNT:-}" ]; then
    GOMP_SPINCOUNT=20000
    export GOMP_SPINCOUNT
fi
script=$1; shift
exec FreeFem++ -nw -v 0 "$script" "$@"
