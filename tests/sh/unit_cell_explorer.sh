#!/bin/sh
# Unit-cell explorer, all five paths with 8 levels each (static amplitudes),
# then the shear path with dynamic amplitudes and shear flow:
# - exit 0; each CSV has the expected header and steps + 1 rows;
# - warp strip: crimp interchange at the end (dA1 < 0, dA2 > 0), and the weft
#   strip the mirror image;
# - shear: the spars are engaged at the largest shear (F_L1, F_L2 > 0) and
#   carry more than at the start;
# - every row: the energies per mechanism (wovenffEnergySplit) add up to W
#   (from wovenffPoint) within 1e-9 relative;
# - the PNGs and summary.json exist and are not empty;
# - dynamic run: gamma_f has flowed (0 < gamma_f < gamma) and the amplitudes
#   stay near their static balance;
# - the new bindings stop with a message on bad input (dt < 0).
# Run from the repository root (tests/run.sh does).
set -u
tmp="${WFF_TEST_TMP:-/tmp}"
out="$tmp/unit_cell_explorer"
rm -rf "$out" "$out.dyn"
steps=8
sh tools/ff.sh freefem_scripts/unit_cell_explorer.edp -steps $steps -out "$out" > "$out.log" 2>&1
rc=$?
tail -4 "$out.log"
[ $rc -eq 0 ] || { echo "explorer exited $rc"; cat "$out.log"; exit 1; }
fail=0

tail_cols="time,lambda1,lambda2,gamma,gamma_f,P11,P22,P12,R1,R2,dA1,dA2,dA1_static,dA2_static,T1,T2,F_I,F_L1,F_L2,M_s,W,K_amp,E_yarn_stretch,E_yarn_bending,E_compaction,E_locking,E_shear"
# check_csv FILE FIRST_COLUMN ROWS
check_csv() {
    f=$1
    [ -s "$f" ] || { echo "missing or empty: $f"; fail=1; return; }
    want="$2,$tail_cols"
    got=$(head -1 "$f")
    [ "$got" = "$want" ] || { echo "$f: header is '$got'"; echo "    want '$want'"; fail=1; }
    rows=$(($(wc -l < "$f") - 1))
    [ "$rows" -eq "$3" ] || { echo "$f: $rows rows, want $3"; fail=1; }
    # energies per mechanism (columns 24..) add up to W (column 22)
    awk -F, 'NR > 1 { s = 0; for (i = 24; i <= NF; i++) s += $i; d = s - $22; if (d < 0) d = -d;
        w = $22 < 0 ? -$22 : $22; if (d > 1e-9 * w + 1e-30) { printf "%s row %d: sum %.15g vs W %.15g\n",
        FILENAME, NR - 1, s, $22; bad = 1 } } END { exit bad }' "$f" || fail=1
}
for p in warp weft equibiaxial; do check_csv "$out/$p.csv" strain $((steps + 1)); done
check_csv "$out/equalforce.csv" yarn_tension $((steps + 1))
check_csv "$out/shear.csv" shear_angle $((steps + 1))

# crimp interchange: the pulled family straightens, the other crimps more
awk -F, 'END { if (!($12 < 0 && $13 > 0)) { print "warp strip: dA1 = " $12 ", dA2 = " $13
    " at the end, want dA1 < 0 < dA2"; exit 1 } }' "$out/warp.csv" || fail=1
awk -F, 'END { if (!($13 < 0 && $12 > 0)) { print "weft strip: dA1 = " $12 ", dA2 = " $13
    " at the end, want dA2 < 0 < dA1"; exit 1 } }' "$out/weft.csv" || fail=1
# equal force: both yarns carry the load parameter
awk -F, 'END { d1 = $16 - $1; d2 = $17 - $1; if (d1 < 0) d1 = -d1; if (d2 < 0) d2 = -d2;
    if (d1 > 1e-6 * $1 || d2 > 1e-6 * $1) { print "equalforce: T = " $16 ", " $17 " vs " $1; exit 1 } }' \
    "$out/equalforce.csv" || fail=1
# locking: spars engaged at the largest shear, and loaded more than at the start
awk -F, 'NR == 2 { f0 = $19 + $20 } END { if (!($19 > 0 && $20 > 0 && $19 + $20 > 10 * f0)) {
    print "shear: F_L = " $19 ", " $20 " at the end (start " f0 ")"; exit 1 } }' "$out/shear.csv" || fail=1

for p in warp weft equibiaxial equalforce shear; do
    for f in "$p.png" "cell_$p.png"; do
        [ -s "$out/$f" ] || { echo "missing or empty: $f"; fail=1; }
    done
done
[ -s "$out/summary.json" ] || { echo "missing or empty: summary.json"; fail=1; }
grep -q '"lock_angle_deg": [0-9]' "$out/summary.json" || { echo "summary.json: no lock angle"; fail=1; }

# dynamic amplitudes and shear flow on the shear path, no pictures
sh tools/ff.sh freefem_scripts/unit_cell_explorer.edp -path shear -steps 6 -amplitudes dynamic \
    -dynamic 1 -plots 0 -out "$out.dyn" > "$out.dyn.log" 2>&1
rc=$?
[ $rc -eq 0 ] || { echo "dynamic explorer exited $rc"; cat "$out.dyn.log"; exit 1; }
check_csv "$out.dyn/shear.csv" shear_angle 7
awk -F, 'END { if (!($6 > 0 && $6 < $5)) { print "dynamic shear: gamma_f = " $6 ", gamma = " $5; exit 1 }
    for (k = 12; k <= 13; k++) { d = $k - $(k + 2); if (d < 0) d = -d;
        if (d > 2e-6) { print "dynamic shear: dA" k - 11 " = " $k " far from static " $(k + 2); exit 1 } } }' \
    "$out.dyn/shear.csv" || fail=1

# binding errors reach the script user
cat > "$tmp/uce_bad_dt.edp" <<'EOF'
load "wovenff"
real[int] F = [1, 0, 0, 1, 0, 0], dA = [0, 0], o(1);
wovenffPointStep("freefem_scripts/materials/kevlar_s706.txt", F, dA, 0.0, -1e-6, o);
EOF
sh tools/ff.sh "$tmp/uce_bad_dt.edp" > "$tmp/uce_bad_dt.log" 2>&1
rc=$?
if [ $rc -ne 8 ] || ! grep -q "wovenffPointStep: dt = -1e-06 must be >= 0" "$tmp/uce_bad_dt.log"; then
    echo "wovenffPointStep with dt < 0: exit $rc"; cat "$tmp/uce_bad_dt.log"; fail=1
fi
exit $fail
