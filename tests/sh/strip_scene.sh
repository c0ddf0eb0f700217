#!/bin/sh
# Strip tension scene, warp and weft, pulled to 0.3 % strain: both CSVs, the
# summary and the plot are written, and the load per width grows with strain.
set -u
out="${WFF_TEST_TMP:-/tmp}/strip_scene"
rm -rf "$out"
sh tools/ff.sh freefem_scripts/strip_tension.edp -strain 0.003 -velocity 4 -ramp 2e-4 -out "$out" \
    > "$out.log" 2>&1
rc=$?
tail -4 "$out.log"
[ $rc -eq 0 ] || { echo "scene exited $rc"; exit 1; }
fail=0
for f in strip_warp.csv strip_weft.csv summary.json strip.png; do
    [ -s "$out/$f" ] || { echo "missing or empty: $f"; fail=1; }
done
for fam in warp weft; do
    awk -F, 'NR > 1 { last = $3; strain = $2 } END { if (!(strain >= 0.003 && last > 0)) {
        print FILENAME ": final strain " strain ", load " last; exit 1 } }' "$out/strip_$fam.csv" || fail=1
done
exit $fail
