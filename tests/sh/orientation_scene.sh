#!/bin/sh
# The ballistic scene's -orientation DEG (the warp at DEG to x): a quarter
# model at 90 (its mirror planes hold), the full specimen struck off the centre
# at 30 with the energy balance closed, summary.json "orientation"; bad values
# (a quarter model at 45, a non-number, a non-finite angle) are clear errors
# (exit 2, naming the option and the way out).
set -u
tmp="${WFF_TEST_TMP:-/tmp}"
out="$tmp/orientation_scene"
fail=0
run() { sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse -plots 0 -vtkdt 1e-3 "$@"; }
num() { sed -n "s/.*\"$1\": \([^,}]*\).*/\1/p" "$2/summary.json" | head -1; }  # (the first: the top level)
# a quarter model at 90 degrees
dir="$out-90"
rm -rf "$dir"
run -tend 5e-5 -orientation 90 -out "$dir" > "$dir.log" 2>&1 || { echo "90: scene failed"; tail -3 "$dir.log"; fail=1; }
[ "$(num symmetry "$dir")" = 4 ] && [ "$(num orientation "$dir")" = 90 ] \
    || { echo "90: symmetry $(num symmetry "$dir"), orientation $(num orientation "$dir")"; fail=1; }
# the full specimen at 30 degrees, off the centre
dir="$out-30"
rm -rf "$dir"
run -tend 0.2e-3 -orientation 30 -impact 0.02,-0.01 -out "$dir" > "$dir.log" 2>&1
rc=$?
tail -1 "$dir.log"
if [ $rc -ne 0 ]; then
    echo "30: scene exited $rc"; tail -3 "$dir.log"; fail=1
else
    err=$(num max_energy_error "$dir"); peak=$(num peak_displacement "$dir")
    echo "30 deg, off the centre: symmetry $(num symmetry "$dir"), orientation $(num orientation "$dir"), peak $peak m, largest energy error $err"
    [ "$(num symmetry "$dir")" = 1 ] && [ "$(num orientation "$dir")" = 30 ] || { echo "30: summary"; fail=1; }
    awk -v e="$err" 'BEGIN { exit !(e < 1e-3 && e > -1e-3) }' || { echo "30: energy error $err"; fail=1; }
    awk -v p="$peak" 'BEGIN { exit !(p > 0.9 * 22 * 0.2e-3 && p < 22 * 0.2e-3 + 1e-5) }' \
        || { echo "30: apex peak $peak m does not follow the projectile"; fail=1; }
fi
bad() {
    want=$1; shift
    run -tend 1e-5 -out "$out-bad" "$@" > "$out-bad.log" 2>&1
    rc=$?
    if [ $rc -ne 2 ] || ! grep -q -- "$want" "$out-bad.log"; then
        echo "'$*': exit $rc, wanted 2 and '$want':"; tail -3 "$out-bad.log"; fail=1
    else
        grep -m1 -- "$want" "$out-bad.log"
    fi
}
bad "use the full specimen: strike off the centre with -impact X,Y" -orientation 45
bad "use the full specimen" -orientation 89.5
bad "orientation" -orientation abc
bad "orientation" -orientation inf
exit $fail
