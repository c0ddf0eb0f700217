#!/bin/sh
# Impact speed ladder on the coarse ballistic scene, 0.2 ms each
# (docs/limits.md): at 1, 22 and 100 m/s with the default step (dtfactor 0.8)
# and at 300 m/s with the step the instability message suggests there
# (dtfactor 0.4), the run completes with
#   - every energy-balance error below 1e-5 of the impact energy,
#   - no NaN or Inf anywhere in history.csv,
#   - the largest penetration of the nose into the fabric below 1e-9 m,
#   - the apex never ahead of the projectile nose (z <= tip + penetration + 1 nm:
#     the inelastic contact leaves round-off gaps of ~1e-11 m),
#   - the projectile slowed, never sped up;
# the history's energy_<mechanism> columns add up to internal_energy;
# 300 m/s at the default step too, held by the amplitudes' travel limit
# (docs/model.md §12); and 300 m/s at the default step without that limit
# (-travel 0) is stopped by the instability detector, before any NaN, with
# "suggested -dtfactor 0.4" (exit 4, summary failed).
set -u
tmp="${WFF_TEST_TMP:-/tmp}/speed_ladder"
rm -rf "$tmp"
mkdir -p "$tmp"
scene=freefem_scripts/ballistic_impact.edp
fail=0
printf '  %-8s %-8s %-8s %-12s %-12s %-12s %s\n' speed dtfactor steps apex_mm max_error max_pen_m v_end
for case in "1 0.8" "22 0.8" "100 0.8" "300 0.4" "300 0.8"; do
    set -- $case
    v=$1; df=$2; out="$tmp/v${v}_$df"
    sh tools/ff.sh "$scene" -mesh coarse -tend 0.2e-3 -plots 0 -vtkdt 1 -velocity "$v" -dtfactor "$df" \
        -out "$out" > "$out.log" 2>&1
    rc=$?
    if [ $rc -ne 0 ]; then echo "v = $v m/s, dtfactor $df: exit $rc"; tail -3 "$out.log"; fail=1; continue; fi
    if grep -qiE 'nan|inf' "$out/history.csv"; then echo "v = $v: NaN or Inf in history.csv"; fail=1; fi
    pen=$(sed -n 's/.*"max_penetration": \([^,]*\),.*/\1/p' "$out/summary.json")
    steps=$(sed -n 's/.*"steps": \([^,]*\),.*/\1/p' "$out/summary.json")
    awk -F, -v v="$v" -v df="$df" -v pen="$pen" -v steps="$steps" '
        NR == 1 { next }
        { e = $9 < 0 ? -$9 : $9; if (e > worst) worst = e
          if ($2 > $3 + pen + 1e-9) { printf "v = %s: apex %.9g ahead of the nose %.9g at t = %g\n", v, $2, $3, $1; bad = 1 }
          if ($4 > v * (1 + 1e-12)) { printf "v = %s: projectile sped up to %.12g\n", v, $4; bad = 1 }
          apex = $2; vend = $4 }
        END {
          printf "  %-8s %-8s %-8s %-12.4g %-12.3g %-12.3g %.6g\n", v, df, steps, apex * 1e3, worst, pen, vend
          if (worst > 1e-5) { print "  energy error too large"; bad = 1 }
          if (pen > 1e-9) { print "  penetration too large"; bad = 1 }
          exit bad }' "$out/history.csv" || fail=1
done
# per-mechanism stored energy (King cell): columns energy_<mechanism> that add
# up to internal_energy
h="$tmp/v22_0.8/history.csv"
for col in energy_yarn_stretch energy_yarn_bending energy_compaction energy_locking energy_shear; do
    head -1 "$h" | tr ',' '\n' | grep -qx "$col" || { echo "history.csv lacks $col"; fail=1; }
done
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i ~ /^energy_/ && $i != "energy_error") m[++n] = i; next }
    { s = 0; for (k = 1; k <= n; k++) s += $m[k]; d = s - $6; if (d < 0) d = -d
      if (d > worst) worst = d; if ($6 > big) big = $6 }
    END { printf "  energy split: %d mechanisms sum to internal_energy within %.2e J (of %.4g J)\n", n, worst, big
          exit !(n == 5 && worst <= 1e-6 * big) }' "$h" || { echo "energy split does not add up"; fail=1; }
out="$tmp/v300_default"
sh tools/ff.sh "$scene" -mesh coarse -tend 0.2e-3 -plots 0 -vtkdt 1 -velocity 300 -travel 0 \
    -out "$out" > "$out.log" 2>&1
rc=$?
[ $rc -eq 4 ] || { echo "300 m/s at dtfactor 0.8: exit $rc, want 4 (stopped as unstable)"; fail=1; }
grep -qF "suggested -dtfactor 0.4" "$out.log" || { echo "300 m/s: no suggested -dtfactor 0.4"; fail=1; }
grep -q '"status": "failed"' "$out/summary.json" || { echo "300 m/s: summary not failed"; fail=1; }
grep -qi 'nan' "$out/history.csv" && { echo "300 m/s: NaN reached the history"; fail=1; }
grep -m1 '^error:' "$out.log" | cut -c1-220 | sed 's|^|  300 m/s at 0.8: |'
grep -qF "the fastest DOF: node " "$out.log" || { echo "300 m/s: the message names no DOF"; fail=1; }
# the same with the adaptive step: it goes back, halves the step and finishes
out="$tmp/v300_adaptive"
sh tools/ff.sh "$scene" -mesh coarse -tend 0.2e-3 -plots 0 -vtkdt 1 -velocity 300 -travel 0 \
    -adaptive 1 -out "$out" > "$out.log" 2>&1
rc=$?
cuts=$(sed -n 's/.*"step_cuts": \([^,]*\),.*/\1/p' "$out/summary.json")
err=$(sed -n 's/.*"max_energy_error": \([^,]*\),.*/\1/p' "$out/summary.json")
echo "  300 m/s at 0.8, -travel 0 -adaptive 1: exit $rc, step_cuts $cuts, largest energy error $err"
[ $rc -eq 0 ] || { echo "300 m/s adaptive: exit $rc"; tail -3 "$out.log"; fail=1; }
awk -v c="$cuts" -v e="$err" 'BEGIN { exit !(c >= 1 && c <= 8 && e < 1e-5 && e > -1e-5) }' \
    || { echo "300 m/s adaptive: step_cuts '$cuts', energy error '$err'"; fail=1; }
# a pack (3 plies) at 300 m/s: the same back-and-halve, the pack's accounts in the snapshot
out="$tmp/v300_pack_adaptive"
sh tools/ff.sh "$scene" -mesh coarse -tend 0.2e-3 -plots 0 -vtkdt 1 -velocity 300 -travel 0 \
    -adaptive 1 -plies 3 -out "$out" > "$out.log" 2>&1
rc=$?
cuts=$(sed -n 's/.*"step_cuts": \([^,]*\),.*/\1/p' "$out/summary.json")
err=$(sed -n 's/.*"max_energy_error": \([^,]*\),.*/\1/p' "$out/summary.json")
echo "  3 plies at 300 m/s, -travel 0 -adaptive 1: exit $rc, step_cuts $cuts, largest energy error $err"
[ $rc -eq 0 ] || { echo "3 plies at 300 m/s adaptive: exit $rc"; tail -3 "$out.log"; fail=1; }
awk -v c="$cuts" -v e="$err" 'BEGIN { exit !(c >= 1 && c <= 8 && e < 1e-4 && e > -1e-4) }' \
    || { echo "3 plies at 300 m/s adaptive: step_cuts '$cuts', energy error '$err'"; fail=1; }
exit $fail
