#!/bin/sh
# The 2/2 basket cell (basket_2x2, kevlar_basket.txt) runs in the strip scene
# by changing only the material file: a warp strip pulled to 0.3 % strain
# exits 0, writes its CSV, and ends with a positive load per width.
set -u
out="${WFF_TEST_TMP:-/tmp}/basket_strip"
rm -rf "$out"
mkdir -p "$out"
material=freefem_scripts/materials/kevlar_basket.txt
sh tools/ff.sh freefem_scripts/strip_tension.edp -material "$material" \
    -strain 0.003 -velocity 4 -ramp 2e-4 -family warp -plots 0 -out "$out" > "$out.log" 2>&1
rc=$?
tail -3 "$out.log"
[ $rc -eq 0 ] || { echo "scene exited $rc"; exit 1; }
[ -s "$out/strip_warp.csv" ] || { echo "missing or empty: strip_warp.csv"; exit 1; }
grep -qF "\"material\": \"$material\"" "$out/summary.json" \
    || { echo "summary.json does not name the basket material"; exit 1; }
awk -F, 'NR > 1 { last = $3; strain = $2 } END { if (!(strain >= 0.003 && last > 0)) {
    print FILENAME ": final strain " strain ", load per width " last " N/m"; exit 1 }
    print "warp strip at strain " strain ": " last " N/m" }' "$out/strip_warp.csv"
