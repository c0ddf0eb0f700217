#!/bin/sh
# The new-cell tutorial (docs/new_cell.md) works as written:
#  (a) every repository file it names exists;
#  (b) its test binaries build (make) and pass;
#  (c) its strip-scene command runs: taken from the tutorial line itself, with
#      a tiny strain, a quick pull and its -out replaced by the test folder
#      (an option given twice is an error). The strip of
#      straight linear yarns has an analytic load: S_1 x strain per width,
#      within 5 % at the end of the pull;
#  (d) its bad-material commands (with /tmp/ replaced by the test folder) stop
#      the scene as the tutorial says: exit 4, a failed summary.json whose error
#      is the message the tutorial prints;
#  (e) its ballistic command runs with the 1 N preload (a cell without
#      amplitudes), shortened: the preload stretch is the analytic one,
#      1 + 1 N / (S_1 x yarn_spacing_1), the strain to 1e-5 relative
#      (summary.json gives the stretch to 10 digits: the strain to ~4e-6).
# Run from the repository root (tests/run.sh does).
set -u
doc=docs/new_cell.md
material=freefem_scripts/materials/kevlar_linear.txt
out="${WFF_TEST_TMP:-/tmp}/tutorial_cell"
rm -rf "$out"
mkdir -p "$out"
fail=0

# (a) the files the tutorial names: every `path/with/a.ext` in backquotes that
# lies in the repository (results/, build/ and /tmp are outputs), plus the ones
# the steps depend on
[ -f "$doc" ] || { echo "missing $doc"; exit 1; }
named=$(grep -o '`[A-Za-z0-9_./-]*/[A-Za-z0-9_.-]*\.[a-z]*`' "$doc" | tr -d '`' |
        grep -v -e '^results/' -e '^build/' -e '^/' | sort -u)
for f in $named plugin/cells/linear_yarns.c "$material" tests/data/linear_symmetric.txt \
         tests/c/test_cells.c tests/c/test_linear_yarns.c tests/c/lib/cell_suite.c \
         include/wovenff/cell.h include/wovenff/material.h freefem_scripts/strip_tension.edp \
         tools/ff.sh; do
    [ -f "$f" ] || { echo "$doc names $f, which does not exist"; fail=1; }
done
grep -qF '"freefem_scripts/materials/kevlar_linear.txt"' tests/c/test_cells.c ||
    { echo "tests/c/test_cells.c has no case for $material"; fail=1; }

# (b) build (a no-op after make) and run the two C tests of steps 4 and 5
if ! make -s build/tests/test_cells build/tests/test_linear_yarns > "$out/make.log" 2>&1; then
    echo "make failed:"; tail -20 "$out/make.log"; exit 1
fi
for t in build/tests/test_cells build/tests/test_linear_yarns; do
    "$t" > "$out/$(basename "$t").log" 2>&1 || {
        echo "$t failed:"; tail -20 "$out/$(basename "$t").log"; fail=1; }
    tail -1 "$out/$(basename "$t").log"
done

# (c) the tutorial's strip command, exactly as written, plus the quick options
cmd=$(grep -m1 "^sh tools/ff.sh freefem_scripts/strip_tension.edp -material $material" "$doc")
[ -n "$cmd" ] || { echo "$doc has no strip-scene command with $material"; exit 1; }
cmd=$(printf '%s' "$cmd" | sed 's/ -out [^ ]*//')
eval "$cmd -strain 0.003 -velocity 2 -ramp 4e-4 -frame 5e-5 -plots 0 -out \"\$out/strip\"" \
    > "$out/strip.log" 2>&1
rc=$?
[ $rc -eq 0 ] || { echo "strip scene exited $rc:"; tail -20 "$out/strip.log"; exit 1; }
csv="$out/strip/strip_warp.csv"
[ -s "$csv" ] || { echo "missing or empty: $csv"; exit 1; }
S1=$(sed -n 's/^S_1 *= *\([0-9.eE+-]*\).*/\1/p' "$material")
[ -n "$S1" ] || { echo "no S_1 in $material"; exit 1; }
awk -F, -v S="$S1" 'NR > 1 { strain = $2; load = $3 }
    END {
        want = S * strain
        printf "strip end: strain %.5f, load per width %.1f N/m, S_1 x strain %.1f N/m (ratio %.4f)\n",
               strain, load, want, load / want
        if (!(strain >= 0.003 && load > 0)) { print "final strain or load wrong"; exit 1 }
        if (!(load > 0.95 * want && load < 1.05 * want)) { print "load off S_1 x strain by more than 5 %"; exit 1 }
    }' "$csv" || fail=1

# (d) the bad material: the tutorial's two commands, writing into the test folder
bad_sed=$(grep -m1 "^sed 's/^G .*/G = -1/' $material > /tmp/bad_linear.txt" "$doc")
bad_run=$(grep -m1 "^sh tools/ff.sh freefem_scripts/strip_tension.edp -material /tmp/bad_linear.txt" "$doc")
if [ -z "$bad_sed" ] || [ -z "$bad_run" ]; then
    echo "$doc has no bad-material commands"; fail=1
else
    eval "$(printf '%s' "$bad_sed" | sed "s|/tmp/|$out/|g")"
    eval "$(printf '%s' "$bad_run" | sed "s|/tmp/|$out/|g") -plots 0" > "$out/bad.log" 2>&1
    rc=$?
    [ $rc -eq 4 ] || { echo "bad material: scene exited $rc, the tutorial says 4"; tail -5 "$out/bad.log"; fail=1; }
    summary="$out/bad_linear/summary.json"
    grep -q '"status": "failed"' "$summary" 2>/dev/null ||
        { echo "bad material: no failed summary.json"; fail=1; }
    message="/bad_linear.txt:8: key 'G' = -1: shear stiffness must be >= 0 N/m"
    grep -qF "$message" "$summary" 2>/dev/null ||
        { echo "bad material: summary.json lacks '$message'"; fail=1; }
    tr '\n' ' ' < "$doc" | tr -s ' ' | grep -qF "/tmp$message" ||
        { echo "$doc does not print '/tmp$message'"; fail=1; }
fi

# (e) the ballistic command with the preload, cut short
cmd=$(grep -m1 "^sh tools/ff.sh freefem_scripts/ballistic_impact.edp -material $material" "$doc")
cmd=$(printf '%s' "$cmd" | sed 's/ -out [^ ]*//')
[ -n "$cmd" ] || { echo "$doc has no ballistic command with $material"; exit 1; }
case "$cmd" in *-preload*) echo "the tutorial's ballistic command sets -preload: $cmd"; fail=1 ;; esac
eval "$cmd -tend 1e-4 -plots 0 -out \"\$out/ballistic\"" > "$out/ballistic.log" 2>&1
rc=$?
[ $rc -eq 0 ] || { echo "ballistic scene exited $rc:"; tail -20 "$out/ballistic.log"; exit 1; }
stretch=$(sed -n 's/.*"preload_stretch": *\[\([0-9.eE+-]*\),.*/\1/p' "$out/ballistic/summary.json")
spacing=$(sed -n 's/^yarn_spacing_1 *= *\([0-9.eE+-]*\).*/\1/p' "$material")
awk -v l="$stretch" -v S="$S1" -v s="$spacing" 'BEGIN {
        want = 1 / (S * s)
        printf "ballistic preload: strain %.6g, 1 N / (S_1 x spacing) %.6g\n", l - 1, want
        if (!(l - 1 > 0) || !((l - 1) / want > 1 - 1e-5 && (l - 1) / want < 1 + 1e-5)) {
            print "preload strain is not 1 N / (S_1 x yarn_spacing_1)"; exit 1 }
    }' || fail=1
exit $fail
