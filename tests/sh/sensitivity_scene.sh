#!/bin/sh
# The sensitivity scene on a two-input study of the ballistic scene (coarse
# mesh, to 2.2 ms, 2 jobs): it completes, writes sensitivity.csv, .json and a
# tornado chart per observable, and its normalised sensitivities of the peak
# displacement equal, to the printed precision, the finite differences this
# test computes by hand from its own runs of the ballistic scene:
#   K_I (log spacing: 4.15e-3 .. 1.66e-2 N spans a factor 4), two runs:
#     S = ln(y_high / y_low) / ln(x_high / x_low)
#   velocity (linear, 18 .. 26 m/s), those two runs and the base run:
#     S = (y_high - y_low) / (x_high - x_low) * x_base / y_base
# Morris screening on one input and one trajectory: mu* is the elementary effect
# computed by hand from the design's two runs.
# A run that fails (a = -1e5 1/m: the material is refused) is listed with its
# error and leaves its input's sensitivities empty; the study still exits 0.
# Bad inputs stop with exit code 2 before anything is run: an unknown input,
# low >= high, a non-number, out of range, -jobs 0, base options the scene
# refuses, the mesh in a Morris design.
# test-runner: first (~30 s: one of the longest tests; tests/run.sh starts the longest first)
set -u
tmp="${WFF_TEST_TMP:-/tmp}/sensitivity_scene"
rm -rf "$tmp"; mkdir -p "$tmp"
fail=0
base="-mesh coarse -tend 2.2e-3"
study="$tmp/study"
sh tools/ff.sh freefem_scripts/sensitivity.edp -base "$base" -inputs "K_I:4.15e-3:1.66e-2,velocity:18:26" \
    -jobs 2 -out "$study" > "$tmp/study.log" 2>&1
rc=$?
tail -8 "$tmp/study.log"
[ $rc -eq 0 ] || { echo "study exited $rc"; exit 1; }
for f in sensitivity.csv sensitivity.json tornado_peak_displacement.png tornado_peak_time.png \
         tornado_apex_history_l2.png tornado_warp_weft_difference.png tornado_clamp_slip.png \
         tornado_rebound_speed.png; do
    [ -s "$study/$f" ] || { echo "missing or empty: $f"; fail=1; }
done
grep -q '"runs": 5, "runs_failed": 0' "$study/sensitivity.json" || { echo "sensitivity.json: not 5 runs, 0 failed"; fail=1; }
[ "$(grep -c ',' "$study/sensitivity.csv")" -eq 13 ] || { echo "sensitivity.csv: not 2 x 6 rows"; fail=1; }
grep -q '\[5/5\]' "$tmp/study.log" || { echo "no progress line [5/5]"; fail=1; }

# by hand: the ballistic scene at the ends of each range, and the base
run() { # name, options...
    name=$1; shift
    sh tools/ff.sh freefem_scripts/ballistic_impact.edp $base -plots 0 -vtkdt 1 -out "$tmp/$name" "$@" \
        > "$tmp/$name.log" 2>&1 || { echo "run $name failed"; fail=1; }
}
peak() { sed -n 's/^  "peak_displacement": \([^,]*\),$/\1/p' "$tmp/$1/summary.json"; }
run ki_low -set K_I=4.15e-3
run ki_high -set K_I=1.66e-2
run v_low -velocity 18
run v_high -velocity 26
run base
scene_value() { # input, observable: the sensitivity column of sensitivity.csv
    awk -F, -v i="$1" -v o="$2" '$1 == i && $2 == o { print $13 }' "$study/sensitivity.csv"
}
want_ki=$(awk -v yl="$(peak ki_low)" -v yh="$(peak ki_high)" \
    'BEGIN { printf "%.6g", (log(yh) - log(yl)) / (log(1.66e-2) - log(4.15e-3)) }')
want_v=$(awk -v yl="$(peak v_low)" -v yh="$(peak v_high)" -v y0="$(peak base)" \
    'BEGIN { printf "%.6g", (yh - yl) / (26 - 18) * 22 / y0 }')
got_ki=$(scene_value K_I peak_displacement)
got_v=$(scene_value velocity peak_displacement)
echo "K_I: scene $got_ki, by hand $want_ki; velocity: scene $got_v, by hand $want_v"
[ -n "$want_ki" ] && [ "$got_ki" = "$want_ki" ] || { echo "K_I sensitivity differs"; fail=1; }
[ -n "$want_v" ] && [ "$got_v" = "$want_v" ] || { echo "velocity sensitivity differs"; fail=1; }
# the by-hand runs are the study's runs: the same peak, to the digit
for side in low high; do
    grep -q "\"peak_displacement\": $(peak v_$side | awk '{ printf "%.6g", $1 }')[,}]" "$study/sensitivity.json" \
        || { echo "velocity_$side: the study's peak differs from the run by hand"; fail=1; }
done

# Morris, one input, one trajectory: mu* = |ln(y_b / y_a) / ln(x_b / x_a)| from the design's two runs
sh tools/ff.sh freefem_scripts/sensitivity.edp -base "$base" -inputs "K_I:4.15e-3:1.66e-2" -method morris \
    -trajectories 1 -jobs 2 -out "$tmp/morris" > "$tmp/morris.log" 2>&1 || { echo "Morris study failed"; fail=1; }
mx() { sed -n "s/.*\"name\": \"morris_0_$1\".*K_I=\([^']*\)'.*/\1/p" "$tmp/morris/sensitivity.json"; }
my() { sed -n 's/^  "peak_displacement": \([^,]*\),$/\1/p' "$tmp/morris/runs/"*"_morris_0_$1/summary.json"; }
want_m=$(awk -v xa="$(mx 0)" -v xb="$(mx 1)" -v ya="$(my 0)" -v yb="$(my 1)" \
    'BEGIN { e = (log(yb) - log(ya)) / (log(xb) - log(xa)); printf "%.6g", (e < 0 ? -e : e) }')
got_m=$(awk -F, '$1 == "K_I" && $2 == "peak_displacement" { print $7 }' "$tmp/morris/sensitivity.csv")
echo "Morris K_I: scene mu* $got_m, by hand $want_m (x $(mx 0) -> $(mx 1))"
[ -n "$want_m" ] && [ "$got_m" = "$want_m" ] || { echo "Morris mu* differs"; fail=1; }

# a failed run is listed with its error; its input has no sensitivity; exit 0
sh tools/ff.sh freefem_scripts/sensitivity.edp -base "$base" -inputs "a:-1e5:2e5" -plots 0 \
    -out "$tmp/failed" > "$tmp/failed.log" 2>&1
rc=$?
[ $rc -eq 0 ] || { echo "study with a failed run exited $rc, want 0"; fail=1; }
grep -q '"runs_failed": 1' "$tmp/failed/sensitivity.json" || { echo "failed run not counted"; fail=1; }
grep -q '"status": "failed", "exit_code": 4, "error": "[^"]*key .a. = -1e5: must be > 0' "$tmp/failed/sensitivity.json" \
    || { echo "failed run without its status and error in sensitivity.json"; fail=1; }
grep -q '^failed run a_low: ' "$tmp/failed.log" || { echo "failed run not reported"; fail=1; }
[ "$(awk -F, '$1 == "a" && $2 == "peak_displacement" { print $13 }' "$tmp/failed/sensitivity.csv")" = "" ] \
    || { echo "an input with a failed run has a sensitivity"; fail=1; }

# bad inputs: exit 2, one clear line, nothing run
expect() { # name, pattern, options...
    name=$1; pattern=$2; shift 2
    sh tools/ff.sh freefem_scripts/sensitivity.edp -base "$base" -out "$tmp/$name" "$@" > "$tmp/$name.log" 2>&1
    rc=$?
    [ $rc -eq 2 ] || { echo "$name: exit $rc, want 2"; fail=1; }
    grep -qF -- "$pattern" "$tmp/$name.log" || { echo "$name: output lacks '$pattern'"; sed 's/^/    | /' "$tmp/$name.log" | tail -3; fail=1; }
    [ ! -e "$tmp/$name/sensitivity.csv" ] || { echo "$name: results were written"; fail=1; }
}
expect unknown_input "'K_x' is neither a numeric key" -inputs "K_x:1:2"
expect low_above_high "velocity:26:18': low must be below high" -inputs "velocity:26:18"
expect equal_ends "K_d:1e8:1e8': low must be below high" -inputs "K_d:1e8:1e8"
expect not_a_number "velocity:fast:26': low and high must be numbers" -inputs "velocity:fast:26"
expect out_of_range "massfactor:0.5:2': massfactor must be real>=1" -inputs "massfactor:0.5:2"
expect jobs_zero "-jobs 0: must be >= 1" -inputs "velocity:18:26" -jobs 0
expect morris_mesh "mesh:coarse:fine': not in a Morris design" -inputs "mesh:coarse:fine" -method morris
base="-mesh coarse -velocity fast"   # base options the ballistic scene refuses
expect bad_base "the base options do not run in ballistic_impact: -velocity 'fast' is not a number" \
    -inputs "K_I:4e-3:1e-2"
exit $fail
