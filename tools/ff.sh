#!/bin/sh
# Run a FreeFEM script with wovenff's module and .idp library on the paths.
# Usage: tools/ff.sh script.edp [script arguments...]
# Run from the repository root (the Makefile does).
root=$(cd "$(dirname "$0")/.." && pwd)
FF_LOADPATH="$root/build;/usr/lib/freefem++"
FF_INCLUDEPATH="$root/freefem_scripts/lib;$root/freefem_scripts;/usr/include/freefem++/idp"
export FF_LOADPATH FF_INCLUDEPATH
script=$1; shift
exec FreeFem++ -nw -v 0 "$script" "$@"
