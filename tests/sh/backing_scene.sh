#!/bin/sh
# The backing block through the ballistic scene (issue 30 item 1; docs/backing.md),
# coarse and short: one ply struck by the default ball at 22 m/s on Roma
# Plastilina clay (-backing clay, 4 mm elements under the impact) to 0.5 ms:
#   - summary.json's backface_signature (the top face's deepest point now),
#     crater_diameter and crater_volume are written and positive, the signature
#     at most the dynamic peak backing_peak_depth; crater.csv (x, depth) whose
#     deepest point is the signature's; crater.png drawn; backing.vtu whole;
#   - the energy balance, which holds the block's own account (kinetic + stored
#     + dissipated − the contacts' work on it) beside its contacts' work on the
#     fabric and projectile, within 1 %, and the contacts' loss not negative
#     beyond 0.1 % of the energy given (a contact does not create energy);
#   - the clay resists: the projectile at 0.5 ms is slower than on the same
#     ply without a backing;
#   - the run ends where the crater has settled (-settle 1; a coarse block, 0.1 ms
#     windows), the same settling found with -settle 0, which runs on to -tend;
#   - checkpointed at 0.1 ms and restarted: the uninterrupted run's history.csv,
#     state_hash and signature, byte for byte;
#   - straps (-straps 200 N) in place of the clamp: the edge slips in by 0.5 ms,
#     the balance within 1 %;
#   - refusals naming the options: -backing sand; -backing with -obliquity
#     and with -adapt (which features combine: plugin/combine.c); -straps without
#     a backing, and with a clamp option; the block's own options (-backingmu,
#     -settletol) without one.
# test-runner: first (~50 s: one of the longest tests; tests/run.sh starts the longest first)
set -u
base="${WFF_TEST_TMP:-/tmp}/backing_scene"
fail=0
run() { # name, options
    name=$1; shift
    rm -rf "$base.$name"
    sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse -tend 0.5e-3 -vtkdt 1 \
        -out "$base.$name" "$@" > "$base.$name.log" 2>&1 ||
        { tail -5 "$base.$name.log"; echo "$name: the run failed"; fail=1; }
}
value() { # name, key
    sed -n "s/^  \"$2\": \([^,]*\),*\$/\1/p" "$base.$1/summary.json" | head -1
}
run clay -backing clay -plots 1
run bare -plots 0
[ $fail = 0 ] || exit 1
bfs=$(value clay backface_signature); peak=$(value clay backing_peak_depth)
dia=$(value clay crater_diameter); vol=$(value clay crater_volume)
err=$(value clay max_energy_error); loss=$(value clay backing_contact_loss)
vc=$(value clay final_projectile_velocity); vb=$(value bare final_projectile_velocity)
echo "clay: back-face signature $bfs m (peak $peak m), crater $dia m across, $vol m^3;" \
     "energy error $err, contact loss $loss J; projectile $vc m/s (bare ply: $vb m/s);" \
     "the block $(value clay backing_elements) elements, $(value clay backing_seconds) s of" \
     "$(value clay wall_seconds) s"
awk -v b="$bfs" -v p="$peak" -v d="$dia" -v v="$vol" 'BEGIN {
    if (!(b > 1e-3)) { print "backface_signature " b " m: not a crater"; exit 1 }
    if (!(b <= p + 1e-12)) { print "backface_signature " b " above the dynamic peak " p; exit 1 }
    if (!(d > 0 && v > 0)) { print "crater diameter " d ", volume " v ": not positive"; exit 1 }
}' || fail=1
awk -v e="$err" -v l="$loss" 'BEGIN {
    given = 0.5 * 0.104 * 22 * 22
    if (!(e < 0.01)) { print "largest energy error " e ": not within 1 %"; exit 1 }
    if (!(l > -1e-3 * given)) { print "the contacts created " -l " J"; exit 1 }
}' || fail=1
awk -v c="$vc" -v b="$vb" 'BEGIN { if (!(c < b)) { print "projectile " c " m/s on clay, not slower than the bare ply'"'"'s " b; exit 1 } }' || fail=1
head -1 "$base.clay/crater.csv" | grep -qx 'x,depth' || { echo "crater.csv: header not x,depth"; fail=1; }
deep=$(awk -F, 'NR > 1 && $2 > m { m = $2 } END { printf "%.12g", m }' "$base.clay/crater.csv")
awk -v d="$deep" -v b="$bfs" 'BEGIN { if (!(d <= b + 1e-12 && d >= 0.999 * b)) { print "crater.csv deepest " d " against the signature " b; exit 1 } }' || fail=1
[ -s "$base.clay/crater.png" ] || { echo "crater.png not drawn"; fail=1; }
tail -1 "$base.clay/backing.vtu" | grep -qx '</VTKFile>' && grep -q 'NumberOfCells="1859"' "$base.clay/backing.vtu" \
    || { echo "backing.vtu: not a whole grid of the block's 1859 cells"; fail=1; }
# a checkpoint at 0.1 ms restarted: the uninterrupted run's history and state, byte for byte
short="-mesh coarse -vtkdt 1 -backing clay -tend 0.2e-3 -plots 0"
rm -rf "$base.whole" "$base.part"
sh tools/ff.sh freefem_scripts/ballistic_impact.edp $short -out "$base.whole" > "$base.whole.log" 2>&1 ||
    { tail -3 "$base.whole.log"; echo "whole: the run failed"; fail=1; }
sh tools/ff.sh freefem_scripts/ballistic_impact.edp $short -checkpoint 5 -stopafter 10 \
    -out "$base.part" > "$base.part.log" 2>&1   # (exit 9: stopped there on purpose)
sh tools/ff.sh freefem_scripts/ballistic_impact.edp $short -restart "$base.part" \
    > "$base.restart.log" 2>&1 || { tail -3 "$base.restart.log"; echo "restart failed"; fail=1; }
cmp -s "$base.whole/history.csv" "$base.part/history.csv" &&
    [ "$(value whole state_hash)" = "$(value part state_hash)" ] &&
    [ "$(value whole backface_signature)" = "$(value part backface_signature)" ] ||
    { echo "restarted with a backing: not the uninterrupted run's history and state"; fail=1; }
# the run ends once the crater has settled (-settle 1, the default): a coarse block (8 mm
# elements), windows of 0.1 ms; the ball rebounds at ~1.2 ms. With -settle 0 the same
# settling is found and the run goes on to -tend.
settle="-mesh coarse -vtkdt 1 -backing clay -backingsize 8e-3 -settlewindow 0.1e-3 -plots 0"
for k in 1 0; do
    rm -rf "$base.settle$k"
    sh tools/ff.sh freefem_scripts/ballistic_impact.edp $settle -settle $k -tend 1.8e-3 -out "$base.settle$k" \
        > "$base.settle$k.log" 2>&1 || { tail -3 "$base.settle$k.log"; echo "settle $k: the run failed"; fail=1; }
done
s1=$(value settle1 crater_settle_time); s0=$(value settle0 crater_settle_time)
last1=$(tail -1 "$base.settle1/history.csv" | cut -d, -f1); last0=$(tail -1 "$base.settle0/history.csv" | cut -d, -f1)
echo "settling: -settle 1 ended at $last1 s (settled $s1 s); -settle 0 ran to $last0 s (settled $s0 s)"
[ "$(value settle1 crater_settled)" = true ] && [ "$(value settle0 crater_settled)" = true ] \
    || { echo "settle: crater_settled $(value settle1 crater_settled) / $(value settle0 crater_settled), want true"; fail=1; }
awk -v s1="$s1" -v s0="$s0" -v l1="$last1" -v l0="$last0" 'BEGIN {
    if (!(s1 > 0.5e-3 && s1 < 1.8e-3)) { print "settled at " s1 " s: not after the rebound and before -tend"; exit 1 }
    if (l1 != s1) { print "-settle 1: the history ends at " l1 " s, not where it settled (" s1 " s)"; exit 1 }
    if (s0 != s1) { print "-settle 0 settled at " s0 " s, not at " s1 " s"; exit 1 }
    if (!(l0 > 1.79e-3)) { print "-settle 0 ended at " l0 " s, before -tend"; exit 1 }
}' || fail=1
grep -q "the crater has settled" "$base.settle1.log" || { echo "-settle 1: the terminal does not say it settled"; fail=1; }
# straps in place of the clamp: the edge slips in under the straps' light hold (fixed: none)
run straps -backing clay -straps 200 -plots 0
slip=$(value straps max_clamp_slip); serr=$(value straps max_energy_error)
echo "straps 200 N: the edge slipped $slip m by 0.5 ms, energy error $serr"
awk -v s="$slip" -v e="$serr" 'BEGIN { if (!(s > 1e-5 && e < 0.01)) { print "straps: slip " s " m, energy error " e; exit 1 } }' || fail=1
refused() { # name, wanted text, options
    name=$1; want=$2; shift 2
    sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse -tend 1e-5 -plots 0 \
        -out "$base.$name" "$@" > "$base.$name.log" 2>&1
    rc=$?
    if [ $rc -ne 2 ] || ! grep -q -- "$want" "$base.$name.log"; then
        echo "$name: exit $rc, want 2 naming '$want'"; tail -3 "$base.$name.log"; fail=1
    fi
}
refused sand "-backing" -backing sand
refused oblique "backing" -backing clay -obliquity 30
refused adapt "backing" -backing clay -adapt 5
refused strapsbare "-straps" -straps 100
refused strapsclamp "-straps replaces the clamp" -backing clay -straps 100 -clamp fixed
refused mubare "-backingmu sets the backing block" -backingmu 0.5
refused settlebare "-settletol sets the backing block" -settletol 0.05
[ $fail = 0 ] && echo "backing_scene: ok"
exit $fail
