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
#  - the words of limit.png are the terminal's (what the scene hands gnuplot, seen
#    through a gnuplot stand-in on PATH that logs its -e settings): the fit line and
#    the bracket's V50, whose half gap is exact (the speeds are multiples of 0.01);
#    a fit whose V_bl sits at its bound (-stopbelow: the residual jumps from 0 at
#    the limit) says "at its bound" on the terminal, in limit.json and on the
#    picture, naming the bound; a fitted a > 1 is flagged with the speed above
#    which the law's residual passes the striking speed; a plain fit warns nothing;
#  - a scene that never perforates: exit 5, the error names -vmax;
#  - every run of a round failing: exit 4; bad options: exit 2.
# test-runner: first (~24 s: one of the longest tests; tests/run.sh starts the longest first)
set -u
tmp="${WFF_TEST_TMP:-/tmp}/limit_scene"
rm -rf "$tmp"; mkdir -p "$tmp"
fail=0
standin=tests/edp/scenes/lambert_jonas_standin.edp
# gnuplot on PATH logs each call's script and -e settings (into $tmp/OUT.gnuplot)
gp=$(command -v gnuplot)
if [ -n "$gp" ]; then
    mkdir -p "$tmp/bin"
    printf '#!/bin/sh\nprintf "%%s\\t%%s\\n" "$3" "$2" >> "${WFF_GNUPLOT_CALLS:-/dev/null}"\nexec "%s" "$@"\n' "$gp" > "$tmp/bin/gnuplot"
    chmod +x "$tmp/bin/gnuplot"
fi
sweep() { # out, options...
    out=$1; shift
    PATH="$tmp/bin:$PATH" WFF_GNUPLOT_CALLS="$tmp/$out.gnuplot" \
        sh tools/ff.sh freefem_scripts/ballistic_limit.edp -scene $standin -out "$tmp/$out" "$@" > "$tmp/$out.log" 2>&1
}
# the words limit.gp was given, as gnuplot reads them: fit_text, bracket_text, warning1..3
words() { # out
    vars=$(awk -F'\t' '$1 ~ /limit[.]gp$/ { print $2 }' "$tmp/$1.gnuplot" 2>/dev/null | tail -1)
    [ -n "$vars" ] && "$gp" -e "$vars" -e 'print fit_text; print bracket_text; print warning1; print warning2; print warning3' 2>&1
}
terminal_fit() { sed -n 's/^Lambert-Jonas fit: \(.*\) ([0-9]* perforating runs.*/\1/p' "$tmp/$1.log"; }
terminal_bracket() { sed -n 's/^V50 .* m\/s (fit), \(.*\)$/\1/p' "$tmp/$1.log"; }
field() { # file, key (a number of "key": {"value": X ...} or "key": X)
    sed -n "s/^  \"$2\": {\"value\": \([^,]*\),.*/\1/p; s/^  \"$2\": \([0-9.e+-]*\),$/\1/p" "$1"
}
close() { # what, got, want, relative tolerance
    awk -v g="$2" -v w="$3" -v t="$4" 'BEGIN { d = g - w; if (d < 0) d = -d; exit !(g != "" && d <= t * w) }' \
        || { echo "$1: got '$2', want $3 (tol $4)"; fail=1; }
}

# 1. bracketing downwards, 2 jobs, the files, the fit
sweep law -base "-law 120,0.9,2.5" -vmin 150 -vmax 300 -jobs 2 -runs 10 -threat fsp17
rc=$?
tail -4 "$tmp/law.log"
[ $rc -eq 0 ] || { echo "sweep exited $rc"; cat "$tmp/law.log"; exit 1; }
d="$tmp/law"
for f in limit.csv limit.json limit.png; do [ -s "$d/$f" ] || { echo "missing or empty: $f"; fail=1; }; done
grep -q 'every run perforated: slower' "$tmp/law.log" || { echo "no downward expansion round"; fail=1; }
grep -q '\[2/2\]' "$tmp/law.log" || { echo "no progress line [2/2]"; fail=1; }
grep -q '"threat": "fsp17"' "$d/v150/summary.json" || { echo "-threat fsp17 not passed to the runs"; fail=1; }
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

# 1a. the picture's words are the terminal's, one rounding; the half gap exact; no warning
if [ -n "$gp" ]; then
    w=$(words law)
    [ "$(echo "$w" | sed -n 1p)" = "$(terminal_fit law)" ] && [ -n "$(terminal_fit law)" ] \
        || { echo "limit.png's fit '$(echo "$w" | sed -n 1p)', the terminal's '$(terminal_fit law)'"; fail=1; }
    [ "$(echo "$w" | sed -n 2p)" = "$(terminal_bracket law)" ] && [ -n "$(terminal_bracket law)" ] \
        || { echo "limit.png's bracket '$(echo "$w" | sed -n 2p)', the terminal's '$(terminal_bracket law)'"; fail=1; }
    [ -z "$(echo "$w" | sed -n 3p)" ] || { echo "a plain fit warned on limit.png: $(echo "$w" | sed -n 3p)"; fail=1; }
    echo "limit.png: $(echo "$w" | sed -n 1p); V50 $(echo "$w" | sed -n 2p)"
fi
grep -q '^warning:' "$tmp/law.log" && { echo "a plain fit warned: $(grep '^warning:' "$tmp/law.log")"; fail=1; }
grep -q 'at its bound' "$tmp/law.log" && { echo "a plain fit said 'at its bound'"; fail=1; }
# the half gap, to 0.001 m/s: (lowest perforated - highest stopped below it) / 2 from limit.csv
want=$(awk -F, 'NR > 1 && $3 == 1 && (p == "" || $1 < p) { p = $1 } NR > 1 && $3 == 0 { s[NR] = $1 }
                END { for (k in s) if (s[k] < p && s[k] > h) h = s[k]; printf "%.3f +- %.3f", (p + h) / 2, (p - h) / 2 }' "$d/limit.csv")
got=$(terminal_bracket law | awk '{ printf "%.3f +- %.3f", $1, $3 }')
[ "$got" = "$want" ] || { echo "the bracket's V50 '$(terminal_bracket law)', from limit.csv $want"; fail=1; }

# 1c. V_bl at its bound: runs below 130 m/s stop though the law (V_bl 100) would perforate
sweep bound -base "-law 100,0.9,2.5 -stopbelow 130" -vmin 100 -vmax 300 -jobs 2 -runs 10
rc=$?
[ $rc -eq 0 ] || { echo "the at-bound sweep exited $rc"; tail -5 "$tmp/bound.log"; fail=1; }
stopped=$(awk -F, 'NR > 1 && $3 == 0 && $1 > h { h = $1 } END { print h }' "$tmp/bound/limit.csv")
grep '^Lambert-Jonas fit:\|^warning:' "$tmp/bound.log"
terminal_fit bound | grep -q '^V_bl [0-9.]* +- [0-9.e+-]* m/s (at its bound), ' \
    || { echo "the at-bound fit's line does not say 'at its bound': $(terminal_fit bound)"; fail=1; }
grep -q "^warning: V_bl sits at its bound (the highest stopped speed, $stopped m/s)" "$tmp/bound.log" \
    || { echo "no warning naming the bound (the highest stopped speed $stopped m/s)"; fail=1; }
grep -q '"v_bl": {.*"at_bound": true}' "$tmp/bound/limit.json" && grep -q '"warnings": \["V_bl sits at its bound' "$tmp/bound/limit.json" \
    || { echo "limit.json: V_bl not at_bound or no warning"; fail=1; }
if [ -n "$gp" ]; then
    w=$(words bound)
    [ "$(echo "$w" | sed -n 1p)" = "$(terminal_fit bound)" ] || { echo "limit.png's fit '$(echo "$w" | sed -n 1p)'"; fail=1; }
    [ "warning: $(echo "$w" | sed -n 3p)" = "$(grep -m1 '^warning: V_bl' "$tmp/bound.log")" ] \
        || { echo "limit.png's warning '$(echo "$w" | sed -n 3p)' is not the terminal's"; fail=1; }
    [ -s "$tmp/bound/limit.png" ] || { echo "the at-bound sweep: no limit.png"; fail=1; }
fi

# 1d. a fitted a > 1 (1.05: every residual still below its striking speed) is flagged
sweep abig -base "-law 120,1.05,2" -vmin 100 -vmax 300 -jobs 2 -runs 10
rc=$?
[ $rc -eq 0 ] || { echo "the a > 1 sweep exited $rc"; tail -5 "$tmp/abig.log"; fail=1; }
awk -F, 'NR > 1 && $2 != "" && $2 + 0 >= $1 + 0 { print "a > 1: row " NR ": residual " $2 " >= striking " $1; bad = 1 } END { exit bad }' \
    "$tmp/abig/limit.csv" || fail=1
grep '^warning:' "$tmp/abig.log"
# the speed above which a (V^p - V_bl^p)^(1/p) > V: a V_bl / (a^p - 1)^(1/p), 393.56 m/s for 120, 1.05, 2
grep -q '^warning: a 1.05 > 1: the fitted law.s residual speed passes the striking speed above 393.5[0-9] m/s' "$tmp/abig.log" \
    || { echo "a fitted a = 1.05 not flagged (with the speed 393.56 m/s)"; fail=1; }
if [ -n "$gp" ]; then
    [ "warning: $(words abig | sed -n 3p)" = "$(grep -m1 '^warning: a ' "$tmp/abig.log")" ] \
        || { echo "limit.png's warning '$(words abig | sed -n 3p)' is not the terminal's"; fail=1; }
fi

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
