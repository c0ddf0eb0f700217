#!/bin/sh
# Parameter-identification scene end to end on small synthetic data: strips
# and shear, 6 points each, K_I and a fitted from (0.012, 7e4) within bounds.
# fit.json must name both parameters with a value and a standard error, and
# the fitted material, the curves and the plot must be written. Then the
# errors: an unknown parameter and a bad data line stop the scene (exit 4, was 8 before issue 27)
# with a message naming the parameter, or the file and the line.
# Run from the repository root (tests/run.sh does).
set -u
tmp="${WFF_TEST_TMP:-}"
if [ -z "$tmp" ]; then tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT; fi
out="$tmp/fit_scene"
rm -rf "$out"
mkdir -p "$out"
fail=0
sh tools/ff.sh freefem_scripts/fit_parameters.edp -tests strip_warp,strip_weft,shear -n 6 \
    -set K_I=0.010375,a=85000 -params K_I,a -bounds 1e-3:1e-1,1e4:1e6 -start 0.012,7e4 \
    -out "$out" > "$out.log" 2>&1
rc=$?
tail -6 "$out.log"
[ $rc -eq 0 ] || { echo "scene exited $rc"; exit 1; }
for f in synthetic.csv fit.json fitted_material.txt fit_curves.csv fit_points.csv fit.png; do
    [ -s "$out/$f" ] || { echo "missing or empty: $f"; fail=1; }
done
for p in K_I a; do
    grep -q "\"$p\": {\"value\": [0-9.e+-]*, \"std_error\": [0-9.e+-]*," "$out/fit.json" ||
        { echo "fit.json lacks a value and standard error for $p"; fail=1; }
done
for key in residual_norm iterations; do
    grep -q "\"$key\": " "$out/fit.json" || { echo "fit.json lacks $key"; fail=1; }
done
grep -q '"points": 18' "$out/fit.json" || { echo "fit.json: not 18 points"; fail=1; }
grep -q '^# Fitted by wovenff' "$out/fitted_material.txt" || { echo "fitted material lacks its header"; fail=1; }

# expect NAME CODE PATTERN -- ARGS: exit CODE and PATTERN (fixed string) in the output
expect() {
    name=$1; code=$2; pattern=$3; shift 4
    sh tools/ff.sh freefem_scripts/fit_parameters.edp -plots 0 -out "$out/$name" "$@" \
        > "$out/$name.log" 2>&1
    rc=$?
    [ $rc -eq "$code" ] || { echo "$name: exit $rc, want $code"; fail=1; }
    grep -qF -- "$pattern" "$out/$name.log" || {
        echo "$name: output lacks '$pattern':"; tail -3 "$out/$name.log"; fail=1; }
}
expect unknown_param 4 "parameter 'K_X' is not a key" -- -n 3 -tests strip_warp -params K_I,K_X
printf 'test,x,y\nstrip_warp,0.01,1200\nstrip_warp,0.02\n' > "$out/bad.csv"
expect bad_line 4 "$out/bad.csv:3: expected 3 comma-separated fields" -- -data "$out/bad.csv" -params K_I
expect unknown_option 2 "error: fit_parameters: unknown option '-bogus'" -- -bogus 1
expect not_a_number 2 "error: fit_parameters: -maxiter '12x' is not a number" -- -maxiter 12x
expect no_value 2 "error: fit_parameters: option -seed needs a value" -- -seed
expect bad_test 2 "error: fit_parameters: -tests 'strip_warp,bulge': 'bulge' is not one of" -- -tests strip_warp,bulge
for name in unknown_option not_a_number no_value bad_test; do
    [ -e "$out/$name" ] && { echo "$name: the scene wrote $out/$name"; fail=1; }
done
exit $fail
