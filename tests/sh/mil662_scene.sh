#!/bin/sh
# ballistic_limit.edp -method mil662: the MIL-STD-662F up-and-down sequence
# (lib/wff_mil662.idp; the rule's logic plugin/mil662.c, tests/c/test_mil662.c).
#  1. against the stand-in scene (tests/edp/scenes/lambert_jonas_standin.edp, a
#     known limit V_bl 121.7 m/s, seconds): one shot a round fires the documented
#     sequence, 150 C, 150 - 15.24 = 134.76 C, 119.52 P (the first reversal: the
#     step 7.62), 127.14 C, then 119.52 taken -> the step halved: 123.33; the rule
#     met (exit 0), limit.json's keys (method, v50_mil662, mil662_spread,
#     mil662_std, mil662_shots, mil662_outcomes, mil662_status "met", the fit's
#     v_bl and v50_fit beside it), the V50 the mean of the six it names, mil662.csv
#     a row per shot, mil662.png drawn; -backing clay reaches every run; -resume 1
#     takes every shot again and ends with the same sequence;
#  2. a budget too small (-shots 7, two a round): exit 7, "mil662_status":
#     "budget", "v50_mil662": null, the terminal says "no V50";
#  2a. no -vfirst: sighting shots from the Phoenix-Porwal estimate, the first shot from
#     the slowest perforating one's residual, the rule met; four a round: at most two
#     sighting shots a round, none below a stopped one; -shots 6: no room for them,
#     exit 7 with the files;
#  3. option errors (exit 2, naming the option, nothing written): -method bogus,
#     -vfirst not a speed, -plies 0 (the estimate's option), a fit option with mil662, a mil662 option
#     with the fit;
#  4. the real scene, cheapest (one ply, coarse mesh, the default ball, the fixed
#     clamp; its V50 16.3 m/s with the fit: docs/pack_study.md), -vfirst 14 -step 1
#     -stepafter 0.5, two a round, 6 shots: a mixed zone reached and the rule met;
#     every partial below every complete (the outcomes change at one speed between
#     them), the V50 within the six's speeds, the fit beside it. ~40 s on 2 shared
#     cores.
# test-runner: first (~35 s: one of the longest tests; tests/run.sh starts the longest first)
set -u
tmp="${WFF_TEST_TMP:-/tmp}/mil662_scene"
rm -rf "$tmp"; mkdir -p "$tmp"
fail=0
standin=tests/edp/scenes/lambert_jonas_standin.edp
limit() { # out, options...
    out=$1; shift
    sh tools/ff.sh freefem_scripts/ballistic_limit.edp -out "$tmp/$out" "$@" > "$tmp/$out.log" 2>&1
}
key() { sed -n "s/^  \"$2\": \(.*\),$/\1/p" "$tmp/$1/limit.json" | head -1; }
list() { key "$1" "$2" | tr -d '[]" ' | tr ',' ' '; }
# "speed outcome" a line per shot, in firing order
pairs() { awk -v v="$(list "$1" mil662_shots)" -v o="$(list "$1" mil662_outcomes)" \
              'BEGIN { n = split(v, a, " "); split(o, b, " "); for (i = 1; i <= n; i++) print a[i], b[i] }'; }

# 1. the stand-in, one shot a round: the documented sequence, the files, the keys
limit law -scene $standin -method mil662 -vfirst 150 -base "-law 121.7,0.9,2.5" -jobs 1 -backing clay
rc=$?
grep '^MIL-STD-662F:' "$tmp/law.log"
[ $rc -eq 0 ] || { echo "stand-in sequence: exit $rc, want 0"; tail -5 "$tmp/law.log"; fail=1; }
for k in method v50_mil662 mil662_spread mil662_std mil662_shots mil662_outcomes mil662_status v_bl v50_fit v50_bracket; do
    grep -q "^  \"$k\": " "$tmp/law/limit.json" || { echo "limit.json: no \"$k\""; fail=1; }
done
[ "$(key law method)" = '"mil662"' ] && [ "$(key law mil662_status)" = '"met"' ] \
    || { echo "method $(key law method), status $(key law mil662_status)"; fail=1; }
shots=$(list law mil662_shots)
case "$shots" in
    "150 134.76 119.52 127.14 123.33 "*) ;;
    *) echo "the sequence '$shots', want 150 134.76 119.52 127.14 123.33 ..."; fail=1 ;;
esac
# the V50 is the mean of the six it names; each shot's outcome is the law's (complete above 121.7)
six=$(list law mil662_six)
awk -v six="$six" -v v50="$(key law v50_mil662)" -v sp="$(key law mil662_spread)" 'BEGIN {
    n = split(six, s, " "); if (n != 6) { print "six: " n " speeds"; exit 1 }
    lo = s[1]; hi = s[1]; for (k = 1; k <= 6; k++) { m += s[k] / 6; if (s[k] < lo) lo = s[k]; if (s[k] > hi) hi = s[k] }
    d = m - v50; if (d < 0) d = -d
    if (d > 1e-6 || (hi - lo) - sp > 1e-6 || sp - (hi - lo) > 1e-6 || sp > 38.1) { print "V50 " v50 ", spread " sp ", the six " six; exit 1 } }' || fail=1
pairs law | awk '{ want = ($1 > 121.7) ? "complete" : "partial"; if ($2 != want) { print "shot at " $1 ": " $2 ", want " want; bad = 1 } }
                END { exit bad }' || fail=1
n=$(echo "$shots" | wc -w)
[ "$(($(wc -l < "$tmp/law/mil662.csv") - 1))" -eq "$n" ] || { echo "mil662.csv: not $n rows"; fail=1; }
[ -s "$tmp/law/mil662.png" ] || { echo "no mil662.png"; fail=1; }
for d in "$tmp"/law/v*/; do
    grep -q '"backing": "clay"' "$d/summary.json" || { echo "-backing clay did not reach $d"; fail=1; break; }
done

# 1a. -resume 1 into its folder: every shot taken again, the same sequence
limit law -scene $standin -method mil662 -vfirst 150 -base "-law 121.7,0.9,2.5" -jobs 1 -backing clay -resume 1
rc=$?
[ $rc -eq 0 ] && [ "$(list law mil662_shots)" = "$shots" ] && [ "$(grep -c 'taken from the earlier sweep$' "$tmp/law.log")" -eq "$n" ] \
    || { echo "-resume 1: exit $rc, shots '$(list law mil662_shots)', want '$shots', each taken"; fail=1; }

# 2. the budget spent before the rule is met: no V50, said so
limit budget -scene $standin -method mil662 -vfirst 150 -base "-law 121.7,0.9,2.5" -jobs 2 -shots 7
rc=$?
grep '^MIL-STD-662F:' "$tmp/budget.log"
[ $rc -eq 7 ] || { echo "budget: exit $rc, want 7"; fail=1; }
[ "$(key budget mil662_status)" = '"budget"' ] && [ "$(key budget v50_mil662)" = null ] \
    || { echo "budget: status $(key budget mil662_status), V50 $(key budget v50_mil662)"; fail=1; }
grep -q '^MIL-STD-662F: no V50: the shot budget (-shots 7) is spent' "$tmp/budget.log" || { echo "budget: not said"; fail=1; }

# 2a. no -vfirst: sighting shots from the Phoenix-Porwal estimate (one ply, the 104 g ball: the
#     wovenffV50Estimate value, far below the stand-in's 121.7 m/s), 1.5 times faster a round
#     while none perforates; the first shot of the sequence at sqrt(v^2 - v_r^2) of the slowest
#     perforating one (within the bracket of the fastest stopped below it); the rule met
limit sight -scene $standin -method mil662 -base "-law 121.7,0.9,2.5" -jobs 1
rc=$?
grep '^  sighting\|^MIL-STD-662F:' "$tmp/sight.log"
[ $rc -eq 0 ] || { echo "sighting: exit $rc, want 0"; tail -5 "$tmp/sight.log"; fail=1; }
rule=$(key sight mil662_rule)
from=$(echo "$rule" | sed -n 's/.*"vfirst_from": "\([a-z-]*\)".*/\1/p')
est=$(echo "$rule" | sed -n 's/.*"estimate": \([0-9.e+-]*\),.*/\1/p')
nsight=$(echo "$rule" | sed -n 's/.*"sighting_shots": \([0-9]*\),.*/\1/p')
vfirst=$(echo "$rule" | sed -n 's/.*"vfirst": \([0-9.e+-]*\),.*/\1/p')
[ "$from" = sighting ] || { echo "sighting: vfirst_from '$from'"; fail=1; }
# the sighting shots: est, then 1.5 times faster each (none perforating but the last), then vfirst
# from the last one's residual (limit.csv: striking_velocity,residual_velocity,...)
awk -F, -v est="$est" -v n="$nsight" -v vf="$vfirst" -v shots="$(list sight mil662_shots)" '
    NR > 1 { r[$1 + 0] = $2 }
    END { k = split(shots, s, " "); if (n < 2 || k < n + 1) { print "sighting: " n " sighting shots of " k; exit 1 }
          want = est
          for (i = 1; i <= n; i++) { d = s[i] - want; if (d < 0) d = -d
              if (d > 0.011) { print "sighting shot " i ": " s[i] " m/s, want " want; exit 1 }
              perf = s[i] > 121.7; if (perf != (i == n)) { print "sighting shot " i " at " s[i] ": perforated " perf; exit 1 }
              want = 1.5 * s[i] }
          v = s[n]; vr = r[v + 0]; e = sqrt(v * v - vr * vr); lo = s[n - 1]
          if (!(e > lo && e < v)) e = 0.5 * (lo + v)
          d = e - vf; if (d < 0) d = -d
          if (d > 0.011) { print "first shot " vf " m/s, want " e " (from " v " m/s, residual " vr ")"; exit 1 }
          if (s[n + 1] != vf) { print "the sequence starts at " s[n + 1] ", not " vf; exit 1 }
          printf "sighting: estimate %s m/s, %d sighting shots, the first shot at %s m/s\n", est, n, vf }' "$tmp/sight/limit.csv" || fail=1
[ "$(key sight mil662_status)" = '"met"' ] || { echo "sighting: status $(key sight mil662_status)"; fail=1; }

# 2b. sighting with four a round: at most two sighting shots a round (est, 0.8 est, then 1.5
#     and 2.25 times the fastest), none below a stopped one, the rule still met within -shots
limit sight4 -scene $standin -method mil662 -base "-law 121.7,0.9,2.5" -jobs 4
rc=$?
rule=$(key sight4 mil662_rule)
n4=$(echo "$rule" | sed -n 's/.*"sighting_shots": \([0-9]*\),.*/\1/p')
[ $rc -eq 0 ] && [ "$(key sight4 mil662_status)" = '"met"' ] \
    || { echo "sighting, -jobs 4: exit $rc, status $(key sight4 mil662_status), want 0 and met"; fail=1; }
awk -v n="$n4" -v shots="$(list sight4 mil662_shots)" 'BEGIN { k = split(shots, s, " ")
    if (!(n >= 2 && n <= 8)) { print "sighting, -jobs 4: " n " sighting shots"; exit 1 }
    for (i = 3; i <= n; i++) for (j = 1; j < i; j++) if (s[j] < 121.7 && s[i] < s[j]) {
        print "sighting, -jobs 4: shot " i " at " s[i] " below the stopped " s[j]; exit 1 } }' || fail=1
# 2c. no room for sighting shots (-shots 6 leaves none): exit 7, the files written, said why
limit sight6 -scene $standin -method mil662 -base "-law 121.7,0.9,2.5" -jobs 2 -shots 6
rc=$?
[ $rc -eq 7 ] && [ "$(key sight6 mil662_status)" = '"sighting"' ] && [ -s "$tmp/sight6/mil662.csv" ] \
    && grep -q '^MIL-STD-662F: no V50: no sighting shot perforated' "$tmp/sight6.log" \
    || { echo "sighting, -shots 6: exit $rc, status $(key sight6 mil662_status), want 7, sighting, mil662.csv, said"; fail=1; }

# 3. option errors: exit 2, the option named, nothing written
refuse() { # name, pattern, options...
    name=$1; pattern=$2; shift 2
    limit "$name" -scene $standin "$@"
    rc=$?
    [ $rc -eq 2 ] || { echo "$name: exit $rc, want 2"; fail=1; }
    grep -qF -- "$pattern" "$tmp/$name.log" || { echo "$name: no '$pattern'"; head -3 "$tmp/$name.log"; fail=1; }
    [ -e "$tmp/$name" ] && { echo "$name: wrote $tmp/$name"; fail=1; }
    grep -m1 '^error' "$tmp/$name.log" | cut -c1-150
}
refuse bogus "-method" -method bogus
refuse badvfirst "-vfirst 'fast' is not a speed" -method mil662 -vfirst fast
refuse noplies "-plies 0" -method mil662 -plies 0
refuse fitopt "-runs is -method fit's" -method mil662 -vfirst 100 -runs 10
refuse milopt "-shots is -method mil662's" -shots 10

# 4. the real scene, one ply, coarse, fixed clamp: a mixed zone and the rule met
limit real -method mil662 -mesh coarse -vfirst 14 -step 1 -stepafter 0.5 -shots 6 -jobs 2 -base "-clamp fixed"
rc=$?
grep '^MIL-STD-662F:\|^Lambert-Jonas\|^done' "$tmp/real.log"
[ $rc -eq 0 ] || { echo "real sequence: exit $rc, want 0 (the rule met)"; grep '^round\|  v' "$tmp/real.log"; fail=1; }
[ "$(key real mil662_status)" = '"met"' ] || { echo "real: status $(key real mil662_status)"; fail=1; }
pairs real | awk -v v50="$(key real v50_mil662)" -v six="$(list real mil662_six)" '
        $2 == "partial" { np++; if ($1 > hp) hp = $1 } $2 == "complete" { nc++; if (lc == "" || $1 < lc) lc = $1 }
        END { n = split(six, s, " "); lo = s[1]; hi = s[1]; for (k = 1; k <= n; k++) { if (s[k] < lo) lo = s[k]; if (s[k] > hi) hi = s[k] }
              printf "real: %d partial (highest %s m/s), %d complete (lowest %s m/s), V50 %s m/s\n", np, hp, nc, lc, v50
              if (np < 3 || nc < 3) { print "real: no mixed zone"; exit 1 }
              if (!(hp < lc)) { print "real: a partial above a complete (one ply is deterministic)"; exit 1 }
              if (!(v50 >= lo && v50 <= hi)) { print "real: V50 " v50 " outside the six " lo " .. " hi; exit 1 } }' || fail=1
[ "$(key real fit_status)" = '"ok"' ] || { echo "real: no fit beside ($(key real fit_status))"; fail=1; }
exit $fail
