#!/bin/sh
# Strip tension scene, warp and weft, pulled at the default speed (0.25 m/s after a
# 10 ms smooth start) to 1.1 % strain (the default 4 % takes ~2 min: measured in
# docs/limits.md): both CSVs, the summary and the plot are written, and the pull is
# quasi-static: every sample from 0.5 % to 1.1 % strain of both strips is within
# 1 % of the static one-point solution (the load_static column). Measured: warp at
# most 0.73 %, weft 0.79 %; at the earlier default (2 m/s, 1 ms start) the weft was
# 25 % above the static load at 1 % strain and this test fails.
# test-runner: first (~23 s: one of the longest tests; tests/run.sh starts the longest first)
set -u
out="${WFF_TEST_TMP:-/tmp}/strip_scene"
rm -rf "$out"
sh tools/ff.sh freefem_scripts/strip_tension.edp -strain 0.011 -out "$out" > "$out.log" 2>&1
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
near "$out/strip_warp.csv" 0.005 0.011 0.01 || fail=1
near "$out/strip_weft.csv" 0.005 0.011 0.01 || fail=1
grep -q "quasi-static" freefem_scripts/strip_tension.edp || { echo "header: no quasi-static claim to check"; fail=1; }
exit $fail
