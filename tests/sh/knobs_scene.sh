#!/bin/sh
# The ballistic scene's speed/accuracy knobs each reach the model and change
# what they should: -elements quad meshes quads, -set writes and uses a material
# copy with the mechanism off, -amplitudes static and -massfactor lengthen the
# step (here up to the membrane limit of the coarse mesh), -contact all and
# -threads 1 (the default: the cores here) leave the answer as it was. Bad values stop
# with exit 2 and the option's name.
set -u
tmp="${WFF_TEST_TMP:-/tmp}/knobs"
rm -rf "$tmp"; mkdir -p "$tmp"
run() { # name, options...
    name=$1; shift
    sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse -tend 1e-4 -plots 0 -vtkdt 1 \
        -out "$tmp/$name" "$@" > "$tmp/$name.log" 2>&1
}
val() { sed -n "s/.*\"$2\": \([^,]*\),.*/\1/p" "$tmp/$1/summary.json" | head -1; }
apex() { tail -1 "$tmp/$1/history.csv" | cut -d, -f2; }
fail=0
for case in "base" "quad -elements quad" "nolock -set K_d=0" "static -amplitudes static" \
            "heavy -massfactor 10" "all -contact all" "threads -threads 1"; do
    set -- $case
    name=$1; shift
    run "$name" "$@" || { echo "$name: exit $?"; tail -3 "$tmp/$name.log"; fail=1; }
done
[ $fail -eq 0 ] || exit 1
awk -v b="$(val base elements)" -v q="$(val quad elements)" 'BEGIN { if (!(q > 0 && q < b)) {
    print "quad mesh: " q " elements vs " b " triangles"; exit 1 } }' || fail=1
grep -q '^K_d *= *0 ' "$tmp/nolock/material_used.txt" || { echo "no K_d = 0 in material_used.txt"; fail=1; }
grep -q '"set": "K_d=0"' "$tmp/nolock/summary.json" || { echo "summary lacks the -set value"; fail=1; }
for name in static heavy; do
    awk -v b="$(val base dt_min)" -v k="$(val $name dt_min)" -v n="$name" 'BEGIN {
        if (!(k > 1.05 * b)) { print n ": dt_min " k " not above " b; exit 1 } }' || fail=1
done
for name in all threads; do
    awk -v b="$(apex base)" -v k="$(apex $name)" -v n="$name" 'BEGIN {
        d = k - b; if (d < 0) d = -d; if (d > 1e-12 * (b > 0 ? b : -b)) { print n ": apex " k " vs " b; exit 1 } }' || fail=1
done
[ "$(apex nolock)" != "$(apex base)" ] || { echo "-set K_d=0 changed nothing"; fail=1; }
# bad values: exit 2 naming the option
for bad in "-elements hex" "-amplitudes frozen" "-massfactor 0.5" "-contact some" "-threads 0" \
           "-set K_x=1"; do
    set -- $bad
    sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse -tend 1e-5 -plots 0 \
        -out "$tmp/bad" "$@" > "$tmp/bad.log" 2>&1
    rc=$?
    opt=$1
    [ "$opt" = "-set" ] && opt="K_x"
    if [ "$opt" = "K_x" ]; then want=4; else want=2; fi
    [ $rc -eq $want ] && grep -q -- "$opt" "$tmp/bad.log" || {
        echo "$bad: exit $rc (want $want), message:"; tail -2 "$tmp/bad.log"; fail=1; }
done
exit $fail
