#!/bin/sh
# The explorer, the fit and the sensitivity scenes run no shell and write
# through the checked path (issue 11: no shell, every write checked, one run
# per folder):
# - an -out with a single quote and a space ("it's a dir") works: exit 0, the
#   results (and pictures) in that folder;
# - an -out built to break out of shell and gnuplot quoting
#   ("x'; touch $tmp/pwned; '" and a gnuplot backquote) is a folder like any
#   other: exit 0, its results there, and no command in it ran (no pwned file);
# - the explorer's folder is locked like the ballistic scene's: a second run
#   into it is refused (exit 2, the earlier results untouched) unless
#   -overwrite 1;
# - a write failure in the explorer (ulimit -f in a subshell: a CSV row, then
#   a picture) exits 3 with "File too large", a failed summary and no
#   "status": "ok", no .tmp left;
# - the sensitivity scene (a tiny study: coarse, -tend 2e-4, one input, 2 jobs)
#   completes into the hostile folder: 3 runs, none failed, a progress line per
#   run, each run's log moved into its folder, the tornado charts drawn.
# Run from the repository root (tests/run.sh does).
set -u
tmp="${WFF_TEST_TMP:-/tmp}/scenes_no_shell"
rm -rf "$tmp"; mkdir -p "$tmp"
fail=0
quote="$tmp/it's a dir"
hostile="$tmp/x'; touch $tmp/pwned; '\`touch $tmp/pwned_gp\`"
explorer=freefem_scripts/unit_cell_explorer.edp
ex_args="-steps 4 -path warp,shear"
pwned() { # label
    for p in pwned pwned_gp; do
        [ ! -e "$tmp/$p" ] || { echo "$1: a command in the path ran ($tmp/$p exists)"; fail=1; rm -f "$tmp/$p"; }
    done
}
ok_summary() { # label dir
    grep -q '"status": "ok"' "$2/summary.json" 2>/dev/null || { echo "$1: no ok summary in $2"; fail=1; }
}

# ---- the explorer
for case in quote hostile; do
    eval "out=\$$case"
    sh tools/ff.sh "$explorer" $ex_args -out "$out" > "$tmp/explorer_$case.log" 2>&1
    rc=$?
    [ $rc -eq 0 ] || { echo "explorer, $case: exit $rc, want 0"; tail -3 "$tmp/explorer_$case.log"; fail=1; }
    ok_summary "explorer, $case" "$out"
    for f in warp.csv shear.csv cell_warp.dat warp.png cell_shear.png; do
        [ -s "$out/$f" ] || { echo "explorer, $case: missing or empty $f"; fail=1; }
    done
    [ "$(wc -l < "$out/warp.csv")" -eq 6 ] || { echo "explorer, $case: warp.csv has not 1 + 5 rows"; fail=1; }
    pwned "explorer, $case"
done
echo "explorer: -out with a quote and a space, and a hostile -out: exit 0, results there"

# one run per folder: refused (exit 2, results untouched), then -overwrite 1
before=$(cat "$quote/warp.csv" "$quote/summary.json" | cksum)
sh tools/ff.sh "$explorer" $ex_args -out "$quote" > "$tmp/explorer_again.log" 2>&1
rc=$?
[ $rc -eq 2 ] || { echo "explorer into a used folder: exit $rc, want 2"; fail=1; }
grep -q "holds an earlier run's files" "$tmp/explorer_again.log" || { echo "explorer into a used folder: no reason given"; fail=1; }
[ "$(cat "$quote/warp.csv" "$quote/summary.json" | cksum)" = "$before" ] || { echo "explorer: a refused run changed the results"; fail=1; }
sh tools/ff.sh "$explorer" -steps 2 -path weft -overwrite 1 -out "$quote" > "$tmp/explorer_overwrite.log" 2>&1
rc=$?
[ $rc -eq 0 ] || { echo "explorer -overwrite 1: exit $rc, want 0"; fail=1; }
[ -e "$quote/warp.csv" ] && { echo "explorer -overwrite 1: the earlier run's warp.csv is left"; fail=1; }
[ -s "$quote/weft.csv" ] || { echo "explorer -overwrite 1: no weft.csv"; fail=1; }
echo "explorer: a used folder refused (exit 2), -overwrite 1 clears it"

# write failures: a file-size limit (512-byte blocks) hit by a CSV row, then by a picture
for limit in 2 100; do
    out="$tmp/limit_$limit"
    ( ulimit -f "$limit"; exec sh tools/ff.sh "$explorer" $ex_args -out "$out" ) > "$out.log" 2>&1
    rc=$?
    [ $rc -eq 3 ] || { echo "explorer, limit $limit blocks: exit $rc, want 3"; tail -3 "$out.log"; fail=1; }
    grep -q "^error: .*File too large" "$out.log" || { echo "explorer, limit $limit blocks: no 'File too large'"; tail -3 "$out.log"; fail=1; }
    grep -qs '"status": "ok"' "$out/summary.json" && { echo "explorer, limit $limit blocks: summary says ok"; fail=1; }
    grep -qs '"status": "failed"' "$out/summary.json" || { echo "explorer, limit $limit blocks: no failed summary"; fail=1; }
    [ -z "$(find "$out" -name '*.tmp*')" ] || { echo "explorer, limit $limit blocks: .tmp files left"; fail=1; }
    for f in "$out"/*.csv; do
        [ -s "$f" ] || continue
        [ "$(tail -c 1 "$f" | od -An -c | tr -d ' ')" = '\n' ] || { echo "explorer, limit $limit blocks: $f ends mid-row"; fail=1; }
    done
    echo "explorer, limit $limit blocks: exit $rc, $(grep -m1 '^error:' "$out.log" | cut -c1-140)"
done

# ---- the fit scene (with its picture)
for case in quote hostile; do
    eval "out=\$$case/fit"
    sh tools/ff.sh freefem_scripts/fit_parameters.edp -params K_I,a -n 4 -out "$out" > "$tmp/fit_$case.log" 2>&1
    rc=$?
    [ $rc -eq 0 ] || { echo "fit, $case: exit $rc, want 0"; tail -3 "$tmp/fit_$case.log"; fail=1; }
    for f in fit.json fit.gp fitted_material.txt fit_curves.csv fit.png; do
        [ -s "$out/$f" ] || { echo "fit, $case: missing or empty $f"; fail=1; }
    done
    pwned "fit, $case"
done
echo "fit: -out with a quote and a space, and a hostile -out: exit 0, fit.png drawn"

# ---- the sensitivity scene: a tiny study into the hostile folder
out="$hostile/study"
sh tools/ff.sh freefem_scripts/sensitivity.edp -base "-mesh coarse -tend 2e-4" -inputs "velocity:18:26" \
    -jobs 2 -out "$out" > "$tmp/sensitivity.log" 2>&1
rc=$?
[ $rc -eq 0 ] || { echo "sensitivity: exit $rc, want 0"; tail -5 "$tmp/sensitivity.log"; fail=1; }
grep -q '"runs": 3, "runs_failed": 0' "$out/sensitivity.json" 2>/dev/null || { echo "sensitivity: not 3 runs, 0 failed"; fail=1; }
for f in sensitivity.csv tornado_peak_displacement.png; do
    [ -s "$out/$f" ] || { echo "sensitivity: missing or empty $f"; fail=1; }
done
for n in 1 2 3; do
    grep -q "^  \[$n/3\] [a-z_]*: ok (exit 0)" "$tmp/sensitivity.log" || { echo "sensitivity: no progress line [$n/3]"; fail=1; }
done
for d in "$out"/runs/0*; do
    [ -d "$d" ] || continue
    [ -s "$d/run.log" ] && [ "$(cat "$d/exit_code")" = 0 ] || { echo "sensitivity: $d without its run.log or exit_code 0"; fail=1; }
    ok_summary "sensitivity run" "$d"
done
[ -z "$(find "$out/runs" -maxdepth 1 -name '*.log')" ] || { echo "sensitivity: a run's log left beside its folder"; fail=1; }
pwned "sensitivity"
echo "sensitivity: a tiny study into a hostile -out: exit $rc, $(grep -c '^  \[' "$tmp/sensitivity.log") runs reported"
exit $fail
