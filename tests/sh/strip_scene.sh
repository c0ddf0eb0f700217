#!/bin/sh
# Strip tension scene, warp and weft, pulled at the default speed (2 m/s, 1 ms
# ramp) to 4 % strain: both CSVs, the summary and the plot are written, and the
# explicit strip follows the static one-point solution (the load_static
# column) where the load has left the toe of the curve:
#   warp  every sample at 2.5-4 % strain within 2 % of static, at 1.8-2.2 % within 4 %
#         (measured: at most 0.74 % over 2.5-4 %, 1.65 % over 1.5-2.5 %);
#   weft  every sample at 3.5-4 % within 6 % (measured: at most 3.4 %; the weft's
#         crimp interchange rings undamped, ~5 % at this pull: 8 % at 3-3.5 %).
# Below ~1.5 % (warp) and ~3 % (weft) the static load is small and the strip's
# ringing is tens of per cent of it: not compared.
set -u
out="${WFF_TEST_TMP:-/tmp}/strip_scene"
rm -rf "$out"
sh tools/ff.sh freefem_scripts/strip_tension.edp -strain 0.04 -out "$out" > "$out.log" 2>&1
rc=$?
tail -4 "$out.log"
[ $rc -eq 0 ] || { echo "scene exited $rc"; exit 1; }
fail=0
for f in strip_warp.csv strip_weft.csv summary.json strip.png; do
    [ -s "$out/$f" ] || { echo "missing or empty: $f"; fail=1; }
done
# near FILE FROM TO TOLERANCE: every sample with FROM <= strain <= TO has
# |load_per_width - load_static| <= TOLERANCE x load_static (at least 3 samples)
near() {
    awk -F, -v from="$2" -v to="$3" -v tol="$4" -v name="$(basename "$1")" '
        NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
        $col["strain"] >= from && $col["strain"] <= to {
            n++; dyn = $col["load_per_width"]; st = $col["load_static"]
            rel = (dyn - st) / st; if (rel < 0) rel = -rel; if (rel > worst) worst = rel
            if (!(st > 0) || rel > tol) { printf "%s: strain %.5f load %.6g N/m, static %.6g: off by %.2f %% (> %.1f %%)\n",
                                                 name, $col["strain"], dyn, st, 100 * rel, 100 * tol; bad = 1 } }
        END { if (n < 3) { printf "%s: only %d samples at strain %g-%g\n", name, n, from, to; bad = 1 }
              else printf "%s: %d samples at strain %g-%g within %.2f %% of static (tolerance %.1f %%)\n",
                          name, n, from, to, 100 * worst, 100 * tol
              exit bad }' "$1"
}
near "$out/strip_warp.csv" 0.025 0.04 0.02 || fail=1
near "$out/strip_warp.csv" 0.018 0.022 0.04 || fail=1
near "$out/strip_weft.csv" 0.035 0.04 0.06 || fail=1
exit $fail
