#!/bin/sh
# The unit-cell explorer's pull-out path (-path pullout; docs/model.md §24, "Pull-out"):
# one king_plain cell whose warp is pulled while the weft is held at -preload's yarn
# tension (1 N), with yarn slip on (-set yarn_friction=0.2, slip_crossovers 170), 20 levels:
# - exit 0; material_used.txt carries the -set value; pullout.csv has 21 rows and the
#   columns pull_strain, T1, T2, F_I, slip_1, slip_2, dissipated_slip;
# - the warp sticks then slides: slip_1 0 on the first row and > 0 on the last, never
#   decreasing; the weft's T2 is 1 N on every row (1e-9); on every row that slid since
#   the row before, T1 = 170 x 0.2 x F_I (the slip tension, 1e-9 relative); the
#   dissipation never decreases and its last value is the sum of the rows' friction
#   work 2 T1 L1_0 ds1 / (4 p0_1 p0_2) (1e-9 relative; L1_0 from the material);
# - summary.json's slip_start_tension_N is the first sliding row's T1; pullout.png drawn,
#   from this CSV (the call gnuplot got, through a stand-in on PATH);
# - without -set (slip off) the path runs, no slip columns, slip_start_tension_N null.
# Run from the repository root (tests/run.sh does).
set -u
tmp="${WFF_TEST_TMP:-/tmp}"
out="$tmp/explorer_pullout"
rm -rf "$out" "$out".*
fail=0
gp=$(command -v gnuplot)
mkdir -p "$tmp/uce_pull_bin"
if [ -n "$gp" ]; then
    printf '#!/bin/sh\nprintf "%%s\\t%%s\\n" "$3" "$2" >> "${WFF_GNUPLOT_CALLS:-/dev/null}"\nexec "%s" "$@"\n' "$gp" > "$tmp/uce_pull_bin/gnuplot"
    chmod +x "$tmp/uce_pull_bin/gnuplot"
fi
PATH="$tmp/uce_pull_bin:$PATH" WFF_GNUPLOT_CALLS="$out.gnuplot" \
    sh tools/ff.sh freefem_scripts/unit_cell_explorer.edp -path pullout -set yarn_friction=0.2 -steps 20 \
    -out "$out" > "$out.log" 2>&1 || { echo "explorer -path pullout exited $?"; cat "$out.log"; exit 1; }
grep -q '^yarn_friction *= *0.2' "$out/material_used.txt" || { echo "material_used.txt lacks yarn_friction = 0.2"; fail=1; }
csv="$out/pullout.csv"
[ "$(($(wc -l < "$csv") - 1))" -eq 21 ] || { echo "$csv: $(($(wc -l < "$csv") - 1)) rows, want 21"; fail=1; }
mat=freefem_scripts/materials/kevlar_s706.txt
p1=$(awk -F'[ =#]+' '$1 == "p0_1" { print $2 }' $mat); p2=$(awk -F'[ =#]+' '$1 == "p0_2" { print $2 }' $mat)
a1=$(awk -F'[ =#]+' '$1 == "A0_1" { print $2 }' $mat)
awk -F, -v p1="$p1" -v p2="$p2" -v a1="$a1" '
    NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i
              split("pull_strain T1 T2 F_I slip_1 slip_2 dissipated_slip", need, " ")
              for (k in need) if (!(need[k] in c)) { print "no column " need[k]; bad = 1; exit 1 }
              next }
    { t1 = $c["T1"]; s = $c["slip_1"]; d = $c["dissipated_slip"]
      e = $c["T2"] - 1; if (e < 0) e = -e; if (e > 1e-9) { print "row " NR - 1 ": T2 " $c["T2"]; bad = 1 }
      if (NR == 2 && s != 0) { print "slip_1 " s " on the first row"; bad = 1 }
      if (NR > 2 && (s < sprev || d < dprev)) { print "row " NR - 1 ": slip or dissipation fell"; bad = 1 }
      if (NR > 2 && s > sprev) {
          slid++
          ts = 170 * 0.2 * $c["F_I"]; e = t1 - ts; if (e < 0) e = -e
          if (e > 1e-9 * ts) { print "row " NR - 1 ": T1 " t1 " sliding, slip tension " ts; bad = 1 }
          work += 2 * t1 * sqrt(p1 * p1 + a1 * a1) * (s - sprev) / (4 * p1 * p2)
      }
      sprev = s; dprev = d; last = d; lasts = s }
    END { if (bad) exit 1
          if (!(lasts > 0) || slid < 3) { print "the warp did not slide (slip " lasts ", " slid " rows)"; exit 1 }
          e = last - work; if (e < 0) e = -e
          if (e > 1e-9 * work) { print "dissipated_slip " last " against the rows friction work " work; exit 1 }
          printf "pull-out: %d of 20 levels slid, slip %.4g, dissipated %.6g J/m^2 (friction work %.6g)\n", slid, lasts, last, work }
' "$csv" || fail=1
first=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next } $c["slip_1"] > 0 { print $c["T1"]; exit }' "$csv")
grep -q "\"slip_start_tension_N\": $first" "$out/summary.json" \
    || { echo "summary.json: slip_start_tension_N is not the first sliding row's T1 ($first)"; grep slip_start "$out/summary.json"; fail=1; }
if [ -n "$gp" ]; then
    [ -s "$out/pullout.png" ] || { echo "no pullout.png"; fail=1; }
    grep "explorer_pullout.gp" "$out.gnuplot" | grep -qF "csv='$csv'" || { echo "pullout.png not drawn from $csv"; cat "$out.gnuplot"; fail=1; }
fi
# slip off: the path runs, nothing slides
sh tools/ff.sh freefem_scripts/unit_cell_explorer.edp -path pullout -steps 4 -plots 0 -out "$out.off" > "$out.off.log" 2>&1 \
    || { echo "explorer -path pullout without slip exited $?"; cat "$out.off.log"; fail=1; }
head -1 "$out.off/pullout.csv" | grep -q slip_1 && { echo "slip columns without slip"; fail=1; }
grep -q '"slip_start_tension_N": null' "$out.off/summary.json" || { echo "slip off: slip_start_tension_N not null"; fail=1; }
exit $fail
