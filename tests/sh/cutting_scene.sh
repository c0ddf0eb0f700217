#!/bin/sh
# Transverse cutting through the ballistic scene (docs/model.md §25; issue 29
# items 3, 4), coarse and short:
#   - one ply at 10 m/s (below its V50 of ~16.5 m/s) with -set
#     cutting_pressure=20e6: a flat nose (-edgeradius 0.2 mm) cuts elements out
#     under its edge by 1.2 ms (from 1.13 ms); the hemisphere does not damage a yarn, and nor
#     does the flat nose without cutting (the cut is the key's doing); the flat
#     nose's peak contact pressure is above the hemisphere's;
#   - the file's cutting_pressure = 0 and a copy of the file without the key
#     give the same history.csv, byte for byte;
#   - a 3-ply pack (flat nose, 30 m/s, cutting on) writes ply_first_damage_time
#     with one entry per ply: a number in (0, t_end] for a ply with failed
#     elements, null for one without, a holed ply damaged no later than the
#     perforation time, the strike face damaged first (the edge cuts it first),
#     and ply_failure.png.
set -u
base="${WFF_TEST_TMP:-/tmp}/cutting_scene"
fail=0
run() { # name, options
    name=$1; shift
    rm -rf "$base.$name"
    sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse -failure on \
        -vtkdt 1 -out "$base.$name" "$@" > "$base.$name.log" 2>&1 ||
        { tail -5 "$base.$name.log"; echo "$name: the run failed"; fail=1; }
}
value() { # name, key
    sed -n "s/^  \"$2\": \([^,]*\),*\$/\1/p" "$base.$1/summary.json" | head -1
}
list() { # name, key
    sed -n "s/^  \"$2\": \[\(.*\)\],*\$/\1/p" "$base.$1/summary.json" | head -1
}
one="-velocity 10 -tend 1.2e-3 -edgeradius 0.2e-3 -plots 0"
run flat_cut $one -nose flat -set cutting_pressure=20e6
run round_cut $one -nose hemisphere -set cutting_pressure=20e6
run flat_off $one -nose flat
sed 's/^cutting_pressure/# cutting_pressure/' freefem_scripts/materials/kevlar_s706.txt > "$base.mat.txt"
run flat_nokey $one -nose flat -material "$base.mat.txt"
[ $fail = 0 ] || exit 1
for n in flat_cut round_cut flat_off; do
    echo "$n: eroded $(value $n eroded_elements), failure energy $(value $n failure_energy) J, peak contact pressure $(value $n contact_pressure_peak) Pa, $(value $n verdict)"
done
awk -v e="$(value flat_cut eroded_elements)" 'BEGIN { exit !(e > 0) }' ||
    { echo "the flat nose with cutting eroded no element"; fail=1; }
for n in round_cut flat_off; do
    awk -v e="$(value $n eroded_elements)" -v f="$(value $n failure_energy)" 'BEGIN { exit !(e == 0 && f == 0) }' ||
        { echo "$n: damaged (eroded $(value $n eroded_elements), failure energy $(value $n failure_energy) J)"; fail=1; }
done
awk -v a="$(value flat_cut contact_pressure_peak)" -v b="$(value round_cut contact_pressure_peak)" \
    'BEGIN { exit !(a > b && b > 0) }' ||
    { echo "the flat edge's peak pressure is not above the hemisphere's"; fail=1; }
cmp -s "$base.flat_off/history.csv" "$base.flat_nokey/history.csv" ||
    { echo "cutting_pressure = 0 and the file without the key differ (history.csv)"; fail=1; }
# the pack
run pack -plies 3 -velocity 30 -tend 1e-3 -nose flat -edgeradius 0.2e-3 -set cutting_pressure=20e6
[ $fail = 0 ] || exit 1
times=$(list pack ply_first_damage_time) failed=$(list pack ply_failed) holed=$(list pack ply_holed)
echo "pack: ply_first_damage_time [$times], ply_failed [$failed], ply_holed [$holed], perforation_time $(value pack perforation_time)"
awk -v t="$times" -v f="$failed" -v h="$holed" -v tp="$(value pack perforation_time)" 'BEGIN {
    tend = 1e-3; if (tp != "null") tp = tp + 0
    n = split(t, T, ","); split(f, F, ","); split(h, H, ",")
    if (n != 3) { print "ply_first_damage_time has " n " entries, not 3"; exit 1 }
    for (p = 1; p <= n; p++) {
        gsub(/ /, "", T[p])
        if (T[p] != "null") T[p] = T[p] + 0
        if (T[p] == "null") { if (F[p] + 0 > 0) { print "ply " p - 1 " failed but no damage time"; exit 1 } continue }
        if (!(T[p] > 0 && T[p] <= tend)) { print "ply " p - 1 ": time " T[p] " outside (0, t_end]"; exit 1 }
        if (F[p] + 0 == 0) { print "ply " p - 1 ": a damage time but no failed element"; exit 1 }
        if (H[p] + 0 == 1 && tp != "null" && T[p] > tp) { print "ply " p - 1 " holed, damaged after the perforation"; exit 1 }
        if (p > 1 && T[1] != "null" && T[p] < T[1]) { print "ply " p - 1 " damaged before the strike face"; exit 1 }
    }
    if (T[1] == "null") { print "the strike face was not damaged"; exit 1 }
}' || fail=1
[ -s "$base.pack/ply_failure.png" ] || { echo "no ply_failure.png"; fail=1; }
exit $fail
