#!/bin/sh
# The ballistic scene's -zonal R: King within R of the impact point, linear yarns
# fitted to King's curves about the preload beyond (freefem_scripts/lib/wff_zonal.idp).
# -zonal 0.04 runs, writes the zonal radius and the element count of each zone to
# summary.json (they add up to the mesh), the far field's material made by the
# fitting tool in the run folder (linear_yarns, softer than straight yarns: the
# crimped King cell's tangent), the same file again on a second run; the energy
# balance closes with two materials; early in the impact (small strains) the apex
# is within 1 % of the all-King run's and not equal to it; a run stopped and
# restarted from a checkpoint ends as the uninterrupted run. Bad values (negative,
# not a number) and -zonal with -adapt or static amplitudes stop with exit 2
# naming the option.
set -u
tmp="${WFF_TEST_TMP:-/tmp}/zonal"
rm -rf "$tmp"; mkdir -p "$tmp"
run() { # name, options...
    name=$1; shift
    sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse -tend 0.5e-3 -plots 0 -vtkdt 1 \
        -out "$tmp/$name" "$@" > "$tmp/$name.log" 2>&1
}
val() { sed -n "s/.*\"$2\": \([^,]*\),.*/\1/p" "$tmp/$1/summary.json" | head -1; }
apex() { tail -1 "$tmp/$1/history.csv" | cut -d, -f2; }
fail=0
for case in "zonal -zonal 0.04" "again -zonal 0.04" "king -zonal 0"; do
    set -- $case
    name=$1; shift
    run "$name" "$@" || { echo "$name: exit $?"; tail -3 "$tmp/$name.log"; fail=1; }
done
[ $fail -eq 0 ] || exit 1
awk -v r="$(val zonal zonal_radius)" -v k="$(val zonal zone_elements_king)" \
    -v f="$(val zonal zone_elements_far)" -v n="$(val zonal elements)" 'BEGIN {
    if (!(r == 0.04 && k > 0 && f > 0 && k + f == n)) {
        print "zones: radius " r ", King " k " + far " f " of " n " elements"; exit 1 } }' || fail=1
awk -v k="$(val king zone_elements_king)" -v f="$(val king zone_elements_far)" \
    -v n="$(val king elements)" 'BEGIN { if (!(k == n && f == 0)) {
    print "-zonal 0: King " k ", far " f " of " n; exit 1 } }' || fail=1
far="$tmp/zonal/far_field/fitted_material.txt"
grep -q '^cell = linear_yarns' "$far" || { echo "no linear_yarns far field in $far"; fail=1; }
awk '/^S_1 *=/ { s = $3 } END { if (!(s > 1e4 && s < 5.15e6)) { print "far field S_1 = " s; exit 1 } }' \
    "$far" || fail=1
sed 1,5d "$far" > "$tmp/a.txt"; sed 1,5d "$tmp/again/far_field/fitted_material.txt" > "$tmp/b.txt"
cmp -s "$tmp/a.txt" "$tmp/b.txt" || { echo "the fitted values differ between two runs"; fail=1; }
awk -v e="$(val zonal max_energy_error)" 'BEGIN { if (!(e >= 0 && e < 1e-4)) {
    print "energy error with two materials " e; exit 1 } }' || fail=1
awk -v z="$(apex zonal)" -v k="$(apex king)" 'BEGIN { d = z - k; if (d < 0) d = -d;
    if (!(d < 0.01 * k && d > 0)) { print "apex " z " vs all-King " k; exit 1 } }' || fail=1
# a checkpointed run stopped after frame 20 and restarted ends where the whole run does
run stop -zonal 0.04 -checkpoint 10 -stopafter 20
rc=$?
[ $rc -eq 9 ] || { echo "stop: exit $rc (want 9)"; tail -3 "$tmp/stop.log"; fail=1; }
run resumed -zonal 0.04 -checkpoint 10 -restart "$tmp/stop" ||
    { echo "restart: exit $?"; tail -3 "$tmp/resumed.log"; fail=1; }
[ "$(apex resumed)" = "$(apex zonal)" ] || { echo "restarted apex $(apex resumed) vs $(apex zonal)"; fail=1; }
# bad values: exit 2 naming the option
for bad in "-zonal -0.02|-zonal" "-zonal abc|-zonal" "-zonal 0.04 -adapt 5|-adapt" \
           "-zonal 0.04 -amplitudes static|-amplitudes"; do
    opts=${bad%|*}; also=${bad#*|}
    sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse -tend 1e-5 -plots 0 \
        -out "$tmp/bad" $opts > "$tmp/bad.log" 2>&1
    rc=$?
    { [ $rc -eq 2 ] && grep -q -- "-zonal" "$tmp/bad.log" && grep -q -- "$also" "$tmp/bad.log"; } || {
        echo "$opts: exit $rc (want 2, naming -zonal and $also), message:"; tail -2 "$tmp/bad.log"
        fail=1; }
done
exit $fail
