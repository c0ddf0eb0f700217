#!/bin/sh
# The ballistic scene struck off the centre (-impact X,Y): the whole square
# (meshes/ballistic_full.geo), coarse and short; the apex node is the node
# under the impact point, the fabric there moves with the projectile, the
# energy balance closes; a flat nose runs too; bad values (-impact outside the
# opening, a malformed X,Y, an unknown nose, -side too small) are clear errors
# (exit 2, naming the option).
set -u
tmp="${WFF_TEST_TMP:-/tmp}"
out="$tmp/impact_anywhere"
fail=0
run() { sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse -plots 0 -vtkdt 1e-3 "$@"; }
num() { sed -n "s/.*\"$1\": \([^,}]*\).*/\1/p" "$2/summary.json"; }
for nose in hemisphere flat; do
    dir="$out-$nose"
    rm -rf "$dir"
    run -tend 0.3e-3 -impact 0.03,-0.02 -nose "$nose" -edgeradius 1.5e-3 -out "$dir" > "$dir.log" 2>&1
    rc=$?
    tail -2 "$dir.log"
    [ $rc -eq 0 ] || { echo "$nose: scene exited $rc"; fail=1; continue; }
    ax=$(num apex_x "$dir"); ay=$(num apex_y "$dir"); sym=$(num symmetry "$dir")
    err=$(num max_energy_error "$dir"); peak=$(num peak_displacement "$dir")
    echo "$nose: apex node at ($ax, $ay), symmetry $sym, peak $peak m, largest energy error $err"
    awk -v x="$ax" -v y="$ay" 'BEGIN { d = (x - 0.03)^2 + (y + 0.02)^2; exit !(d < 1e-18) }' \
        || { echo "$nose: the apex node ($ax, $ay) is not the node under the impact point"; fail=1; }
    [ "$sym" = 1 ] || { echo "$nose: an off-centre impact must model the whole square (symmetry $sym)"; fail=1; }
    awk -v e="$err" 'BEGIN { exit !(e < 1e-3 && e > -1e-3) }' || { echo "$nose: energy error $err"; fail=1; }
    # the fabric under the nose follows it: at 0.3 ms the apex is near V t = 6.6 mm
    awk -v p="$peak" 'BEGIN { exit !(p > 0.9 * 22 * 0.3e-3 && p < 22 * 0.3e-3 + 1e-5) }' \
        || { echo "$nose: apex peak $peak m does not follow the projectile"; fail=1; }
done
# a point at the centre keeps the quarter model (the paper's scene, symmetry 4)
dir="$out-centre"
rm -rf "$dir"
run -tend 2e-5 -impact 0.0,0 -out "$dir" > "$dir.log" 2>&1 || { echo "centre: scene failed"; tail -3 "$dir.log"; fail=1; }
[ "$(num symmetry "$dir")" = 4 ] && [ "$(num apex_x "$dir")" = 0 ] && [ "$(num apex_y "$dir")" = 0 ] \
    || { echo "centre: symmetry $(num symmetry "$dir"), apex ($(num apex_x "$dir"), $(num apex_y "$dir"))"; fail=1; }
bad() {
    want=$1; shift
    run -tend 1e-5 -out "$out-bad" "$@" > "$out-bad.log" 2>&1
    rc=$?
    if [ $rc -ne 2 ] || ! grep -q -- "$want" "$out-bad.log"; then
        echo "'$*': exit $rc, wanted 2 and '$want':"; tail -3 "$out-bad.log"; fail=1
    fi
}
bad "must land inside the opening" -impact 0.2,0
bad "must land inside the opening" -impact 0.125,0
bad "two numbers and a comma" -impact 0.03
bad "two numbers and a comma" -impact 0.03,abc
bad "two numbers and a comma" -impact ,0.01
bad "unknown\|hemisphere|flat|sphere\|one of" -nose cone
bad "more than twice -radius" -side 0.2
bad "larger than the nose radius" -nose flat -edgeradius 0.01
exit $fail
