#!/bin/sh
# Every picture a scene draws from its CSVs shows their numbers in their units
# (issue 27, item 5): a value read off a picture is found in the CSV as it is,
# in the unit its axis names. Each scene runs briefly with its pictures on
# (ballistic_impact plain to the first profile time, the same with yarn slip on
# (slip_0.png), with -failure on and with -plies 2; strip_tension, explicit_loop, fit_parameters; the unit-cell explorer,
# every path, king_plain and basket_2x2; ballistic_limit against its stand-in
# scene, -method fit and mil662), through a gnuplot stand-in on PATH that logs each call's script and
# -e settings. Each logged call is then run again by the real gnuplot with a
# hook before every plot (the axis labels and tic formats in force, and
# `set table`: every point as gnuplot computed it), and
# tests/tools/picture_units.awk checks every data curve against the CSVs the
# call was given: x a CSV column as it is, y (y2, a filled band's height, an
# image's colour) a column, a column plus a constant or the sum or difference
# of two, from the same row, and each axis label's unit the one
# docs/csv_columns.md gives those columns. A curve scaled for display (strain
# in %, N/mm, ms) or labelled with another unit fails, naming the picture, the
# plot and the curve.
# Also checked: every picture the scenes drew was traced (none left out
# unnoticed), and a deliberately rescaled copy of one picture's script fails.
# Pictures drawn from no CSV (the explorer's 3-D cell_P.png from cell_P.dat,
# the sensitivity scene's tornado charts) are not checked here.
# Run from the repository root (tests/run.sh does).
set -u
tmp="${WFF_TEST_TMP:-/tmp}/picture_units"
rm -rf "$tmp"; mkdir -p "$tmp/bin"
fail=0
gp=$(command -v gnuplot) || { echo "gnuplot not found (make deps installs it)"; exit 1; }
# the stand-in: logs "script<TAB>vars" of each call, then draws as gnuplot does
printf '#!/bin/sh\nprintf "%%s\\t%%s\\n" "$3" "$2" >> "${WFF_GNUPLOT_CALLS:-/dev/null}"\nexec "%s" "$@"\n' "$gp" > "$tmp/bin/gnuplot"
chmod +x "$tmp/bin/gnuplot"
scene() { # NAME SCRIPT ARGS...: a scene run into $tmp/NAME, its gnuplot calls into $tmp/NAME.calls
    name=$1; shift
    PATH="$tmp/bin:$PATH" WFF_GNUPLOT_CALLS="$tmp/$name.calls" \
        sh tools/ff.sh "$@" -out "$tmp/$name" > "$tmp/$name.log" 2>&1 \
        || { echo "sh tools/ff.sh $* failed:"; tail -5 "$tmp/$name.log"; fail=1; }
}
impact=freefem_scripts/ballistic_impact.edp
scene impact "$impact" -mesh coarse -tend 0.4e-3 -vtkdt 1 -plots 1
scene slip "$impact" -mesh coarse -tend 0.4e-3 -vtkdt 1 -plots 1 -set yarn_friction=0.2
scene failure "$impact" -mesh coarse -tend 2e-5 -vtkdt 1 -failure on -plots 1
scene pack "$impact" -mesh coarse -tend 2e-5 -vtkdt 1 -plies 2 -plots 1
scene backing "$impact" -mesh coarse -tend 2e-5 -vtkdt 1 -backing clay -plots 1
scene strip freefem_scripts/strip_tension.edp -mesh coarse -strain 0.002 -velocity 25 -ramp 0 -frame 1e-6 -plots 1
scene loop freefem_scripts/explicit_loop.edp -n 6 -tend 2e-5 -plots 1
scene fit freefem_scripts/fit_parameters.edp -params K_I -maxiter 1 -plots 1
scene king freefem_scripts/unit_cell_explorer.edp -steps 6
scene basket freefem_scripts/unit_cell_explorer.edp -material freefem_scripts/materials/kevlar_basket.txt -steps 4 -path warp,equibiaxial,shear
scene limit freefem_scripts/ballistic_limit.edp -scene tests/edp/scenes/lambert_jonas_standin.edp \
    -base "-law 120,0.9,2.5" -vmin 100 -vmax 200 -jobs 2 -runs 6
scene mil662 freefem_scripts/ballistic_limit.edp -scene tests/edp/scenes/lambert_jonas_standin.edp \
    -base "-law 121.7,0.9,2.5" -method mil662 -vfirst 150 -jobs 2

# the hook before each plot: the last plot's table, a marker, the labels in force, the
# script's tic formats for x and y (its `set format` statements become WFFFMT_<axis> = ...: a
# table is written in the axes' formats, so it gets 10 digits), 7777 samples (a function's
# curve: not data), a new table
hook='unset table; print $WFFTAB; print "@plot"; show xlabel; show ylabel; show y2label; show cblabel; print "@format x " . WFFFMT_x; print "@format y " . WFFFMT_y; set format x "%.10g"; set format y "%.10g"; set format y2 "%.10g"; set format cb "%.10g"; set samples 7777; set table $WFFTAB'
init='WFFFMT_x = "% h"; WFFFMT_y = "% h"; WFFFMT_y2 = "% h"; WFFFMT_cb = "% h"; WFFFMT_z = "% h"; set print $WFFTAB; print ""; unset print'
# check NAME SCRIPT VARS: the picture of one logged call
checked=0
check() {
    name=$1; script=$2; vars=$3
    pic=$(printf '%s' "$vars" | sed -n "s/.*out='\([^']*\)\.tmp'.*/\1/p")
    [ -n "$pic" ] || pic=$(sed -n "s/^set output '\(.*\)\.tmp'$/\1/p" "$script")
    label="$name/$(basename "$pic")"
    # the CSVs it was given: quoted paths in its settings or (fit.gp) its own text
    files=$( { printf '%s\n' "$vars"; cat "$script"; } | grep -o "'[^']*\.csv'" | tr -d "'" | sort -u |
             while read -r f; do [ -f "$f" ] && printf '%s ' "$f"; done)
    echo "$pic" >> "$tmp/traced"
    if [ -z "$files" ]; then echo "$label: no CSV (not checked)"; return; fi
    hooked="$tmp/hooked.gp"
    sed 's/\(^\|[;{"]\)\([ \t]*\)\(s\{0,1\}plot[ \t]\)/\1\2@WFFHOOK; \3/g
         s/\(^\|[;{]\)\([ \t]*\)set format \(x\|y\|y2\|cb\|z\) /\1\2WFFFMT_\3 = /g' "$script" > "$hooked"
    "$gp" -e "$vars; out='$tmp/trace.png'" -e "WFFHOOK = '$hook'" -e "$init" \
        "$hooked" -e 'unset table; print $WFFTAB' > "$tmp/trace.txt" 2>&1
    awk -v doc=docs/csv_columns.md -v files="$files" -v picture="$label" -f tests/tools/picture_units.awk \
        "$tmp/trace.txt" || fail=1
    checked=$((checked + 1))
}
for name in impact slip failure pack backing strip loop fit king basket limit mil662; do
    [ -s "$tmp/$name.calls" ] || { echo "$name: no gnuplot call logged"; fail=1; continue; }
    while IFS="$(printf '\t')" read -r script vars; do
        check "$name" "$script" "$vars"
    done < "$tmp/$name.calls"
done

# every picture drawn was traced: the PNGs of the runs against the calls
n_png=0
for png in "$tmp"/*/*.png; do
    [ -e "$png" ] || continue
    n_png=$((n_png + 1))
    grep -qxF "$png" "$tmp/traced" || { echo "$png drawn by no logged call"; fail=1; }
done
[ "$checked" -ge 25 ] || { echo "only $checked pictures checked"; fail=1; }

# the check can fail: strip.gp drawing N/mm (the old picture), or labelling % over the strain as it is
vars=$(awk -F'\t' '$1 ~ /strip[.]gp$/ { print $2 }' "$tmp/strip.calls" | tail -1)
sed "s/(N\/m)/(N\/mm)/; s/(column('load_per_width'))/(column('load_per_width') * 1e-3)/" freefem_scripts/plots/strip.gp \
    > "$tmp/strip_rescaled.gp"
sed "s/'nominal strain (-)'/'nominal strain (%)'/" freefem_scripts/plots/strip.gp > "$tmp/strip_percent.gp"
fail_before=$fail; checked_before=$checked
check rescaled "$tmp/strip_rescaled.gp" "$vars" > "$tmp/rescaled.txt" 2>&1
check percent "$tmp/strip_percent.gp" "$vars" > "$tmp/percent.txt" 2>&1
fail=$fail_before; checked=$checked_before
grep -q "curve \"warp, explicit strip\": the y values are not a quantity of the y label's unit (y: no column, sum or difference of two (rescaled?); y label 'load per width (N/mm)'" "$tmp/rescaled.txt" \
    && grep -q "curve \"warp, static point (GSL)\": the y values .*load_static (N/m).*y label 'load per width (N/mm)'" "$tmp/rescaled.txt" \
    || { echo "a strip picture in N/mm was not caught:"; cat "$tmp/rescaled.txt"; fail=1; }
grep -q "x is strain (-); the x label says 'nominal strain (%)'" "$tmp/percent.txt" \
    || { echo "a strip picture labelled % was not caught:"; cat "$tmp/percent.txt"; fail=1; }
echo "caught: $(grep -m1 'no column' "$tmp/rescaled.txt" | cut -c1-200)"
echo "caught: $(grep -m1 'load_static' "$tmp/rescaled.txt" | cut -c1-200)"
echo "caught: $(grep -m1 'x label says' "$tmp/percent.txt" | cut -c1-200)"
echo "$checked pictures traced ($n_png PNGs drawn)"
exit $fail
