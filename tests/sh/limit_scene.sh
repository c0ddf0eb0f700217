#!/bin/sh
# The ballistic-limit sweep (freefem_scripts/ballistic_limit.edp) driven against a
# stand-in scene that answers a known Lambert-Jonas law (tests/edp/scenes/
# lambert_jonas_standin.edp: no physics, a summary.json as the ballistic scene's
# with -failure on), so the driver is tested in seconds:
#  - law V_bl 120 m/s, a 0.9, p 2.5 with -vmin 150 -vmax 300 (both perforate): the
#    sweep expands downwards until a run stops, runs 2 at once, writes limit.csv (a
#    row per run, each perforated residual the law's), limit.json and limit.png; the
#    fit recovers V_bl, a, p to 1e-4 and the bracket's V50 +- half-gap holds 120;
#  - a run that fails (-failspeeds) is reported with its log's path, listed as
#    failed and skipped; the fit still recovers the law;
#  - 3 perforating runs (no standard errors): the fit and limit.png still come;
#  - a run that ends at -tend undecided (verdict "undecided", or, from a scene
#    without a verdict, not perforated with the projectile still
#    moving in) is not counted as stopped: listed as undecided, naming -tend;
#  - a scene that never perforates: exit 5, the error names -vmax;
#  - every run of a round failing: exit 4; bad options: exit 2.
set -u
tmp="${WFF_TEST_TMP:-/tmp}/limit_scene"
rm -rf "$tmp"; mkdir -p "$tmp"
fail=0
standin=tests/edp/scenes/lambert_jonas_standin.edp
sweep() { # out, options...
    out=$1; shift
    sh tools/ff.sh freefem_scripts/ballistic_limit.edp -scene $standin -out "$tmp/$out" "$@" > "$tmp/$out.log" 2>&1
}
field() { # file, key (a number of "key": {"value": X ...} or "key": X)
    sed -n "s/^  \"$2\": {\"value\": \([^,]*\),.*/\1/p; s/^  \"$2\": \([0-9.e+-]*\),$/\1/p" "$1"
}
close() { # what, got, want, relative tolerance
    awk -v g="$2" -v w="$3" -v t="$4" 'BEGIN { d = g - w; if (d < 0) d = -d; exit !(g != "" && d <= t * w) }' \
        || { echo "$1: got '$2', want $3 (tol $4)"; fail=1; }
}

# 1. bracketing downwards, 2 jobs, the files, the fit
sweep law -base "-law 120,0.9,2.5" -vmin 150 -vmax 300 -jobs 2 -runs 10
rc=$?
tail -4 "$tmp/law.log"
[ $rc -eq 0 ] || { echo "sweep exited $rc"; cat "$tmp/law.log"; exit 1; }
d="$tmp/law"
for f in limit.csv limit.json limit.png; do [ -s "$d/$f" ] || { echo "missing or empty: $f"; fail=1; }; done
grep -q 'every run perforated: slower' "$tmp/law.log" || { echo "no downward expansion round"; fail=1; }
grep -q '\[2/2\]' "$tmp/law.log" || { echo "no progress line [2/2]"; fail=1; }
[ "$(field "$d/limit.json" runs_total)" = 10 ] || { echo "runs_total not 10"; fail=1; }
[ "$(($(wc -l < "$d/limit.csv") - 1))" -eq 10 ] || { echo "limit.csv: not 10 rows"; fail=1; }
close "V_bl" "$(field "$d/limit.json" v_bl)" 120 1e-4
close "a" "$(field "$d/limit.json" a)" 0.9 1e-4
close "p" "$(field "$d/limit.json" p)" 2.5 1e-4
exp=$(field "$d/limit.json" expansions)
[ "${exp:-0}" -ge 1 ] || { echo "expansions '$exp', want >= 1"; fail=1; }
# each perforated row's residual is the law's; V50 of the bracket holds 120
awk -F, 'NR > 1 && $3 == 1 { w = 0.9 * ($1^2.5 - 120^2.5)^(1/2.5); d = $2 - w; if (d < 0) d = -d;
         if (d > 1e-6 * w) { print "row " NR ": residual " $2 ", law " w; bad = 1 } }
         NR > 1 && $3 == 0 && $1 > 120 { print "row " NR ": stopped above V_bl"; bad = 1 }
         END { exit bad }' "$d/limit.csv" || fail=1
v50=$(sed -n 's/.*"v50_bracket": {"value": \([^,]*\), "half_gap": \([^,]*\),.*/\1 \2/p' "$d/limit.json")
awk -v s="$v50" 'BEGIN { split(s, x, " "); d = x[1] - 120; if (d < 0) d = -d; exit !(s != "" && d <= x[2]) }' \
    || { echo "V50 bracket '$v50' does not hold 120"; fail=1; }
[ -s "$d/v300/summary.json" ] && [ -s "$d/v300/run.log" ] || { echo "run folder v300 incomplete"; fail=1; }
[ "$(field "$d/limit.json" runs_undecided)" = 0 ] || { echo "runs_undecided not 0"; fail=1; }
grep -q '"tend": 0.01[,}]' "$d/v300/summary.json" || { echo "the runs were not given the sweep's -tend 10e-3"; fail=1; }

# 1b. a stopped run that ended at -tend with the projectile still moving on: undecided,
#     warned, counted, listed, left out of the bracket and the fit
sweep undecided -base "-law 120,0.9,2.5 -undecided 100:110" -vmin 100 -vmax 300 -jobs 2 -runs 10
rc=$?
[ $rc -eq 0 ] || { echo "undecided sweep exited $rc"; tail -5 "$tmp/undecided.log"; fail=1; }
grep -q '^  v100: undecided: not perforated by -tend.*still moved on (0.5 m/s).*left out.*raise -tend' \
    "$tmp/undecided.log" || { echo "no warning for a run that ended at -tend"; grep v100 "$tmp/undecided.log"; fail=1; }
grep -q '^100,,,undecided,' "$tmp/undecided/limit.csv" || { echo "limit.csv: v100 not listed as undecided"; fail=1; }
grep -q 'every run perforated: slower' "$tmp/undecided.log" || { echo "the undecided run was taken as stopped"; fail=1; }
close "V_bl (a run undecided)" "$(field "$tmp/undecided/limit.json" v_bl)" 120 1e-4
u=$(field "$tmp/undecided/limit.json" runs_undecided)
[ "${u:-0}" -ge 1 ] || { echo "runs_undecided '$u', want >= 1"; fail=1; }
grep -q '"verdict": "undecided"' "$tmp/undecided/v100/summary.json" || { echo "the stand-in's v100 has no verdict undecided"; fail=1; }
# 1c. the same from a scene without a verdict (perforated false, residual 0, failure_end
#     "tend", still moving on): undecided all the same
sweep undecided_old -base "-law 120,0.9,2.5 -undecided 100:110 -verdict 0" -vmin 100 -vmax 300 -jobs 2 -runs 10
rc=$?
[ $rc -eq 0 ] || { echo "undecided_old sweep exited $rc"; tail -5 "$tmp/undecided_old.log"; fail=1; }
grep -q '^100,,,undecided,' "$tmp/undecided_old/limit.csv" || { echo "limit.csv (no verdict): v100 not listed as undecided"; fail=1; }
grep -q '^  "verdict": ' "$tmp/undecided_old/v100/summary.json" && { echo "-verdict 0 wrote a verdict"; fail=1; }

# 2. a failing run: reported, skipped
sweep failing -base "-failspeeds 249:251" -vmin 100 -vmax 400 -jobs 2 -runs 12
rc=$?
[ $rc -eq 0 ] || { echo "sweep with a failing run exited $rc"; tail -5 "$tmp/failing.log"; fail=1; }
grep -q 'v250: FAILED, skipped: .*a failing run at 250 m/s.*(log: .*v250/run.log)' "$tmp/failing.log" \
    || { echo "the failed run is not reported with its log"; grep v250 "$tmp/failing.log"; fail=1; }
grep -q '^250,,,failed,' "$tmp/failing/limit.csv" || { echo "limit.csv: v250 not listed as failed"; fail=1; }
[ "$(field "$tmp/failing/limit.json" runs_failed)" = 1 ] || { echo "runs_failed not 1"; fail=1; }
close "V_bl (a run failed)" "$(field "$tmp/failing/limit.json" v_bl)" 150 1e-4

# 2a. three perforating runs (-minperforated 3: no residual variance, no standard
# errors): the fit is reported and limit.png still drawn
sweep three -base "-law 120,0.9,2.5" -vmin 100 -vmax 300 -jobs 2 -runs 4 -minperforated 3
rc=$?
[ $rc -eq 0 ] || { echo "sweep with 3 perforating runs exited $rc"; tail -5 "$tmp/three.log"; fail=1; }
[ -s "$tmp/three/limit.png" ] || { echo "3 perforating runs: no limit.png"; grep -i gnuplot "$tmp/three.log"; fail=1; }
grep -q '"std_error": null' "$tmp/three/limit.json" || { echo "3 perforating runs: a standard error that is not null"; fail=1; }

# 2b. a run undecided at -tend (above V_bl: it would perforate given the time) is
# not a stopped run: counted so, it would put a stop above the limit
sweep undecided2 -base "-law 120,0.9,2.5 -undecided 149:151" -vmin 150 -vmax 300 -jobs 2 -runs 10
rc=$?
[ $rc -eq 0 ] || { echo "sweep with an undecided run exited $rc"; tail -5 "$tmp/undecided2.log"; fail=1; }
grep -q '^150,,,undecided,' "$tmp/undecided2/limit.csv" \
    || { echo "limit.csv: v150 (undecided at -tend) not listed as undecided"; grep '^150,' "$tmp/undecided2/limit.csv"; fail=1; }
grep -q 'v150: undecided: not perforated by -tend.*raise -tend' "$tmp/undecided2.log" \
    || { echo "the undecided run is not reported naming -tend"; grep v150 "$tmp/undecided2.log"; fail=1; }
awk -F, 'NR > 1 && $3 == 0 && $1 > 120 { print "undecided: row " NR ": stopped above V_bl"; bad = 1 } END { exit bad }' \
    "$tmp/undecided2/limit.csv" || fail=1

# 3. never perforates: the bracket error names -vmax
sweep never -base "-never 1" -jobs 2 -expansions 3
rc=$?
grep '^error' "$tmp/never.log"
[ $rc -eq 5 ] || { echo "never-perforating sweep exited $rc, want 5"; fail=1; }
grep -q '^error: ballistic_limit: no bracket of the limit after 3 expansions.*every run stopped.*raise -vmax' \
    "$tmp/never.log" || { echo "no bracket error naming -vmax"; fail=1; }

# 4. every run of a round fails: exit 4; bad options: exit 2
sweep allfail -base "-failspeeds 0:1e9" -jobs 2
rc=$?
[ $rc -eq 4 ] || { echo "all-failing sweep exited $rc, want 4"; fail=1; }
grep -q '^error: ballistic_limit: every run of round 1 failed' "$tmp/allfail.log" || { echo "no all-failed error"; fail=1; }
for bad in "-vmin 300 -vmax 100" "-runs 3" "-runs 513 -base '-never 1'" "-growth 1" "-base -law" "-base '-velocity 3'" "-base '-tend 1'" "-scene nowhere.edp"; do
    eval sweep bad $bad
    rc=$?
    [ $rc -eq 2 ] || { echo "'$bad' exited $rc, want 2"; fail=1; }
    grep -q '^error: ' "$tmp/bad.log" || { echo "'$bad': no error line"; fail=1; }
    case "$bad" in -runs*) grep -q '^error: .*-runs' "$tmp/bad.log" || { echo "'$bad': the error does not name -runs"; fail=1; };; esac
    rm -rf "$tmp/bad"
done
exit $fail
