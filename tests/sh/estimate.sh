#!/bin/sh
# The cost estimate and its re-estimate (issue 27; lib/wff_estimate.idp,
# docs/limits.md "Cost before it is spent"): the estimate is made with the step
# the model takes (the factor the model runs with, whichever rule set it), and
# summary.json's dtfactor_used is that factor: a pack of 8 plies (the scene's
# 0.8: a pack has no rule of its own), the same with -dtfactor given (that
# one), -failure on (its rule's, tests/sh/verdict.sh). The progress line carries the percentage done and the
# time left, in the ballistic and the strip scene. A run the estimate before it
# lets start but whose re-estimate passes -maxsteps (-adapt refines the mesh
# under the nose: the step shrinks) stops with exit 2, its results so far whole
# (every history row complete, the .pvd index, summary.json "status":
# "stopped" with the reason), and the run left alone takes more steps than
# that -maxsteps: the stop was right.
set -u
tmp="${WFF_TEST_TMP:-/tmp}/estimate"
rm -rf "$tmp"; mkdir -p "$tmp"
fail=0
scene=freefem_scripts/ballistic_impact.edp
num() { sed -n "s/^  \"$2\": \([^,]*\),*$/\1/p" "$1/summary.json" | head -1; }
text() { sed -n "s/^  \"$2\": \"\(.*\)\",*$/\1/p" "$1/summary.json" | head -1; }
# factor DIR: the factor the estimate line names
factor() { sed -n 's/^estimate: .* = dtfactor \([0-9.e+-]*\) x the stable step .*/\1/p' "$1.log"; }

# dtfactor_used: the pack's rule, then -dtfactor given
for case in "rule:" "given:-dtfactor 0.5"; do
    name=${case%%:*} opts=${case#*:}
    dir="$tmp/pack_$name"
    sh tools/ff.sh "$scene" -mesh coarse -plots 0 -vtkdt 1 -plies 8 -tend 2e-5 $opts -out "$dir" > "$dir.log" 2>&1
    rc=$?
    if [ $rc -ne 0 ]; then echo "pack_$name: exit $rc"; tail -5 "$dir.log"; fail=1; continue; fi
    used=$(num "$dir" dtfactor_used) est=$(factor "$dir")
    echo "pack_$name: dtfactor_used $used, the estimate's factor $est"
    [ -n "$used" ] && [ "$used" = "$est" ] || { echo "pack_$name: dtfactor_used '$used', the estimate's '$est'"; fail=1; }
    if [ "$name" = rule ]; then   # (a pack has no rule of its own since issue 26: the scene's 0.8)
        [ "$used" = 0.8 ] || { echo "pack_rule: dtfactor_used '$used', the scene's default 0.8"; fail=1; }
    else
        [ "$used" = 0.5 ] || { echo "pack_given: dtfactor_used '$used', -dtfactor 0.5 given"; fail=1; }
    fi
done

# the strip scene: the estimate before, progress with the percentage done and the time left
dir="$tmp/strip"
sh tools/ff.sh freefem_scripts/strip_tension.edp -family warp -strain 0.002 -plots 0 -out "$dir" > "$dir.log" 2>&1
rc=$?
if [ $rc -ne 0 ]; then echo "strip: exit $rc"; tail -5 "$dir.log"; fail=1
else
    grep -q '^estimate: [0-9.e+]* steps (dt .* = dtfactor 0.8 x the stable step' "$dir.log" || { echo "strip: no estimate line"; fail=1; }
    grep -q '^  warp: t = .* [0-9]* % done, ~[0-9.e+-]* s left (re-estimate ' "$dir.log" || { echo "strip: no percentage and time left"; fail=1; }
    est=$(sed -n 's/^estimate: \([0-9.e+]*\) steps.*/\1/p' "$dir.log") steps=$(num "$dir" steps)
    echo "strip: estimate $est steps, took $steps"
    awk -v e="$est" -v s="$steps" 'BEGIN { exit !(e > 0 && s > 0) }' || { echo "strip: estimate '$est', steps '$steps'"; fail=1; }
fi

# the re-estimate past -maxsteps: -adapt 10 on the coarse mesh. The estimate before
# the run (refused with -maxsteps 1) gives N; with -maxsteps 1.1 N the run starts
# and is stopped once its re-estimate passes it.
dir="$tmp/adapt"
args="-mesh coarse -plots 0 -vtkdt 1e-4 -adapt 10 -tend 1e-3"
sh tools/ff.sh "$scene" $args -maxsteps 1 -out "$dir-refused" > "$dir-refused.log" 2>&1
rc=$?
n=$(sed -n 's/^error: the run would take \([0-9.e+]*\) steps, more than -maxsteps 1 .*/\1/p' "$dir-refused.log")
if [ $rc -ne 2 ] || [ -z "$n" ]; then echo "adapt: -maxsteps 1: exit $rc, no estimate"; tail -3 "$dir-refused.log"; fail=1
else
    max=$(awk -v n="$n" 'BEGIN { printf "%d", 1.1 * n }')
    sh tools/ff.sh "$scene" $args -maxsteps "$max" -out "$dir" > "$dir.log" 2>&1
    rc=$?
    stop=$(grep "^error: at t = .* the run re-estimated takes .* more than -maxsteps $max: stopped at step" "$dir.log")
    echo "adapt: estimate $n steps, -maxsteps $max: exit $rc, $(echo "$stop" | cut -c1-150)"
    [ $rc -eq 2 ] && [ -n "$stop" ] || { echo "adapt: exit $rc, wanted 2 with the re-estimate's message"; tail -3 "$dir.log"; fail=1; }
    [ "$(sed -n 's/^  "status": "\(.*\)",$/\1/p' "$dir/summary.json")" = stopped ] && [ -n "$(text "$dir" stopped_by)" ] \
        || { echo "adapt: summary.json status not 'stopped' with stopped_by"; fail=1; }
    awk -F, 'NR == 1 { n = NF } NF != n { bad = 1 } END { exit bad || NR < 3 }' "$dir/history.csv" \
        || { echo "adapt: history.csv rows not whole"; fail=1; }
    grep -q '</VTKFile>' "$dir/ballistic.pvd" || { echo "adapt: ballistic.pvd not whole"; fail=1; }
    ls "$dir" | grep -q '\.tmp$' && { echo "adapt: a .tmp file left"; fail=1; }
    # left alone, the run takes more steps than that -maxsteps
    sh tools/ff.sh "$scene" $args -out "$dir-free" > "$dir-free.log" 2>&1
    rc=$?
    steps=$(num "$dir-free" steps)
    echo "adapt: left alone, $steps steps"
    [ $rc -eq 0 ] && awk -v s="$steps" -v m="$max" 'BEGIN { exit !(s > m) }' \
        || { echo "adapt: left alone, exit $rc, $steps steps: not more than -maxsteps $max (the stop was wrong)"; fail=1; }
fi
exit $fail
