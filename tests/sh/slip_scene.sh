#!/bin/sh
# Yarn slip at the crossovers through the paper's scene (docs/model.md §24),
# coarse and short (to 0.5 ms): with -set yarn_friction=0.2 (kevlar_s706.txt's
# slip_crossovers = 170) the yarns slip, summary.json's dissipated_slip is > 0
# and the energy balance stays within 1e-6 of the impact energy (the run
# without slip: 2e-8); the VTK frames carry slip_1 and slip_2, a frame without
# slip does not. With -set yarn_friction=0 the run is the default run, its
# history.csv byte for byte (the slip branch does not run).
set -u
base="${WFF_TEST_TMP:-/tmp}/slip_scene"
rm -rf "$base.off" "$base.zero" "$base.on"
run() { # name, extra options
    name=$1; shift
    sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse -tend 0.5e-3 -plots 0 \
        -out "$base.$name" "$@" > "$base.$name.log" 2>&1
}
value() { # file, key
    sed -n "s/^  \"$2\": \([^,]*\),*\$/\1/p" "$1"
}
fail=0
run off || { tail -5 "$base.off.log"; echo "the default run failed"; exit 1; }
run zero -set yarn_friction=0 || { tail -5 "$base.zero.log"; echo "yarn_friction=0 failed"; exit 1; }
run on -set yarn_friction=0.2 || { tail -5 "$base.on.log"; echo "yarn_friction=0.2 failed"; exit 1; }
cmp -s "$base.off/history.csv" "$base.zero/history.csv" ||
    { echo "-set yarn_friction=0 changed history.csv"; fail=1; }
d_off=$(value "$base.off/summary.json" dissipated_slip)
d_on=$(value "$base.on/summary.json" dissipated_slip)
e_off=$(value "$base.off/summary.json" max_energy_error)
e_on=$(value "$base.on/summary.json" max_energy_error)
echo "dissipated_slip: off $d_off J, on $d_on J; max_energy_error: off $e_off, on $e_on"
awk -v d="$d_off" 'BEGIN { exit !(d != "" && d == 0) }' ||
    { echo "without slip dissipated_slip is '$d_off'"; fail=1; }
awk -v d="$d_on" 'BEGIN { exit !(d != "" && d > 0) }' ||
    { echo "with yarn_friction=0.2 dissipated_slip is '$d_on'"; fail=1; }
awk -v e="$e_on" 'BEGIN { exit !(e != "" && e < 1e-6) }' ||
    { echo "with slip the energy error reaches $e_on"; fail=1; }
frame="$base.on/vtk/frame_1.vtu"
grep -q 'Name="slip_1"' "$frame" && grep -q 'Name="slip_2"' "$frame" ||
    { echo "$frame has no slip_1/slip_2 fields"; fail=1; }
grep -q 'Name="slip_1"' "$base.off/vtk/frame_1.vtu" &&
    { echo "a frame without slip carries slip_1"; fail=1; }
exit $fail
