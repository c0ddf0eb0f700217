#!/bin/sh
# The ballistic scene with -adapt (coarse, to 0.6 ms, adaptmesh every 10
# frames): it continues after each transfer with its energy balance within 1 %
# (the balance moves by less than 0.01 % of the reference across a transfer,
# and stays within 1 % throughout), each transfer's energy change is in the
# summary's transfer_energy and stays below 1 % of the impact energy, the
# apex follows the non-adapted run within 3 % (and the projectile's
# retraction), and -adapt with -checkpoint is
# refused (exit 2).
set -u
out="${WFF_TEST_TMP:-/tmp}/adapt_scene"
rm -rf "$out" "$out.plain"
sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse -tend 0.6e-3 -adapt 10 \
    -plots 0 -out "$out" > "$out.log" 2>&1
rc=$?
grep 'adapt at' "$out.log"; tail -2 "$out.log"
[ $rc -eq 0 ] || { echo "scene exited $rc"; exit 1; }
fail=0
n=$(grep -c 'adapt at' "$out.log")
[ "$n" -eq 6 ] || { echo "expected 6 transfers, got $n"; fail=1; }
grep -q '"adapt_count": 6' "$out/summary.json" || { echo "summary adapt_count is not 6"; fail=1; }
# the balance before and after each transfer (percent)
sed -n 's/.*(transfer \([^ ]*\) J), balance \([^ ]*\) % -> \([^ ]*\) %.*/\1 \2 \3/p' "$out.log" |
    awk '{ jump = $3 - $2; if (jump < 0) jump = -jump
           if (jump > 0.01) { print "balance moved by " jump " % across a transfer"; bad = 1 }
           if ($3 > 1 || $3 < -1) { print "balance " $3 " % after a transfer"; bad = 1 }
           e = $1 < 0 ? -$1 : $1; if (e > 0.01 * 26.6) { print "transfer of " $1 " J"; bad = 1 }
           k++ }
         END { if (k != 6) { print "parsed " k " transfers"; bad = 1 } exit bad }' || fail=1
awk -F, 'NR > 1 && ($9 > 0.01 || $9 < -0.01) { printf "energy error %.3g at t = %.6g\n", $9, $1; bad = 1 }
    END { exit bad }' "$out/history.csv" || fail=1
grep -q '"transfer_energy"' "$out/summary.json" || { echo "summary lacks transfer_energy"; fail=1; }
# the same run without -adapt: the apex within 3 % from 0.3 ms on, plus the
# distance the transfers moved the projectile back (the old meshes let the
# nose between their nodes by that much)
sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse -tend 0.6e-3 -plots 0 \
    -out "$out.plain" > "$out.plain.log" 2>&1 || { echo "plain run failed"; fail=1; }
back=$(sed -n 's/.*"adapt_retraction": \([^,]*\),.*/\1/p' "$out/summary.json")
paste -d, "$out/history.csv" "$out.plain/history.csv" | awk -F, -v back="$back" \
    -v m="$(head -1 "$out/history.csv" | tr ',' '\n' | wc -l)" '
    NR > 1 && $1 > 3e-4 { a = $2; b = $(m + 2); d = a - b; if (d < 0) d = -d
        if (d > 0.03 * b + back) { printf "apex %.6g vs %.6g m at %.6g s\n", a, b, $1; bad = 1 } }
    END { exit bad }' || fail=1
# off the centre (the whole square): the apex stays the node under the impact point after
# each transfer, within 5 % of the same run without -adapt from 0.3 ms on
for kind in adapt plain; do
    extra=""; [ $kind = adapt ] && extra="-adapt 20"
    rm -rf "$out.off_$kind"
    sh tools/ff.sh freefem_scripts/ballistic_impact.edp -impact 0.05,0 -mesh coarse -tend 1e-3 -plots 0 \
        $extra -out "$out.off_$kind" > "$out.off_$kind.log" 2>&1 || { echo "off-centre $kind run failed"; fail=1; }
done
paste -d, "$out.off_adapt/history.csv" "$out.off_plain/history.csv" | awk -F, \
    -v m="$(head -1 "$out.off_adapt/history.csv" | tr ',' '\n' | wc -l)" '
    NR > 1 && $1 > 3e-4 { a = $2; b = $(m + 2); d = a - b; if (d < 0) d = -d
        if (d > 0.05 * b) { printf "off-centre: apex %.6g (adapted) vs %.6g m at %.6g s\n", a, b, $1; bad = 1 } }
    END { exit bad }' || fail=1
rm -rf "$out.ck"
sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse -tend 1e-4 -adapt 2 -checkpoint 5 \
    -plots 0 -out "$out.ck" > "$out.ck.log" 2>&1
rc=$?
[ $rc -eq 2 ] && grep -q -- '-adapt 2 with -checkpoint 5: a checkpoint holds one mesh' "$out.ck.log" \
    || { echo "-adapt with -checkpoint: exit $rc"; cat "$out.ck.log"; fail=1; }
exit $fail
