#!/bin/sh
# Make the kernels compiled for one instruction set (every cell and
# membrane.c, linked into one object with ld -r) into a kernel variant that
# links beside the others (the Makefile calls it; plugin/kernel_dispatch.c
# chooses among them at run time).
# Usage: tools/kernel_variant.sh VARIANT IN.o OUT.o ENTRY...
#
#   baseline   the entry points ENTRY (wff_elements_forces, ...) get the
#              suffix __baseline (kernel_dispatch.c defines the names callers
#              use); nothing else changes: the baseline object is the one
#              copy of everything else, and its cells register in "wff_cells".
#   other      every symbol the object defines gets the suffix __VARIANT (so a
#              disassembly names each variant's code); only ENTRY stays global,
#              the rest becomes local to the object; the cell registry section
#              "wff_cells" becomes "wff_cells__VARIANT" (the linker provides its
#              bounds, __start_/__stop_wff_cells__VARIANT).
# Knows nothing of what the object computes.
set -e
variant=$1; in=$2; out=$3; shift 3
map=$out.syms
: >"$map"
if [ "$variant" = baseline ]; then
    defined=$(nm --defined-only -P "$in" | awk '{ print $1 }')
    for entry in "$@"; do
        if printf '%s\n' "$defined" | grep -qx "$entry"; then
            printf '%s %s__baseline\n' "$entry" "$entry" >>"$map"
        fi
    done
    objcopy --redefine-syms="$map" "$in" "$out.part"
else
    keep=""
    for entry in "$@"; do keep="$keep --keep-global-symbol=$entry"; done
    # every defined symbol (functions, their OpenMP and cold parts, data), each
    # name once (the parts' local symbols may share one: all get the suffix)
    nm --defined-only -P "$in" | awk -v s="__$variant" '!seen[$1]++ { print $1, $1 s }' >"$map"
    objcopy $keep "$in" "$out.local"
    objcopy --redefine-syms="$map" --rename-section wff_cells="wff_cells__$variant" \
        "$out.local" "$out.part"
    rm -f "$out.local"
fi
rm -f "$map"
mv "$out.part" "$out"
