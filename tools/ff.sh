#!/bin/sh
# Run a FreeFEM script with wovenff's module and .idp library on the paths.
# Usage: tools/ff.sh script.edp [script arguments...]
# Run from the repository root (the Makefile does).
root=$(cd "$(dirname "$0")/.." && pwd)
FF_LOADPATH="$root/build;/usr/lib/freefem++"
FF_INCLUDEPATH="$root/freefem_scripts/lib;$root/freefem_scripts;/usr/include/freefem++/idp"
export FF_LOADPATH FF_INCLUDEPATH
# OpenMP threads that wait at a barrier sleep instead of spinning (unless the
# caller chose): on a shared machine a spinning thread burns the time slice its
# partner needs, and 2 threads ran 4-5x slower than 1 (docs/limits.md "Threads")
OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-PASSIVE}
export OMP_WAIT_POLICY
script=$1; shift
exec FreeFem++ -nw -v 0 "$script" "$@"
