#!/bin/sh
# The 2/2 basket cell (basket_2x2, kevlar_basket.txt) runs in the strip scene
# by changing only the material file: a warp strip pulled at the default speed
# to 2 % strain exits 0, writes its CSV, names the material in summary.json,
# and follows the static one-point solution (load_static): every sample at
# 1.5-2 % strain within 1.5 % of it (measured: at most 0.47 %; below ~1 % the
# toe's ringing is several per cent of the small static load).
# test-runner: first (~27 s: one of the longest tests; tests/run.sh starts the longest first)
set -u
out="${WFF_TEST_TMP:-/tmp}/basket_strip"
rm -rf "$out"
mkdir -p "$out"
material=freefem_scripts/materials/kevlar_basket.txt
sh tools/ff.sh freefem_scripts/strip_tension.edp -material "$material" \
    -strain 0.02 -family warp -plots 0 -out "$out" > "$out.log" 2>&1
rc=$?
tail -3 "$out.log"
[ $rc -eq 0 ] || { echo "scene exited $rc"; exit 1; }
[ -s "$out/strip_warp.csv" ] || { echo "missing or empty: strip_warp.csv"; exit 1; }
grep -qF "\"material\": \"$material\"" "$out/summary.json" \
    || { echo "summary.json does not name the basket material"; exit 1; }
awk -F, -v from=0.015 -v to=0.02 -v tol=0.015 '
    NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
    $col["strain"] >= from && $col["strain"] <= to {
        n++; dyn = $col["load_per_width"]; st = $col["load_static"]
        rel = (dyn - st) / st; if (rel < 0) rel = -rel; if (rel > worst) worst = rel
        if (!(st > 0) || rel > tol) { printf "strain %.5f: load %.6g N/m, static %.6g: off by %.2f %%\n",
                                             $col["strain"], dyn, st, 100 * rel; bad = 1 } }
    END { if (n < 3) { print "only " n " samples at 1.5-2 % strain"; exit 1 }
          printf "basket warp strip: %d samples at 1.5-2 %% strain within %.2f %% of static (tolerance %.1f %%)\n",
                 n, 100 * worst, 100 * tol; exit bad }' "$out/strip_warp.csv"
