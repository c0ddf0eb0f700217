#!/bin/sh
# The standard threats and the oblique shot in the ballistic scene
# (docs/threats.md): each -threat's mass, diameter and nose as summary.json
# records them, against its specification's numbers (MIL-DTL-46593B for the
# .22 cal FSP, the grain for the RCCs, NIJ 0101.06 and SAAMI for the bullets);
# -mass and -nose given win over the threat's; a 17-grain FSP at 400 m/s on
# the coarse mesh runs with the energy balance closed and slows; the
# projectile's momentum at 0 and 30 degrees of obliquity points along its path
# (30 degrees: the whole square); an oblique chisel run restarted from a
# checkpoint gives the uninterrupted run's history; refusals (exit 2, naming
# the option).
set -u
tmp="${WFF_TEST_TMP:-/tmp}/threats"
rm -rf "$tmp"; mkdir -p "$tmp"
fail=0
run() { sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse -plots 0 -vtkdt 1e-3 "$@"; }
num() { sed -n "s/^ *\"$1\": \([^,}]*\).*/\1/p" "$2/summary.json" | head -1; }
txt() { sed -n "s/^ *\"$1\": \"\([^\"]*\)\".*/\1/p" "$2/summary.json" | head -1; }
# check NAME THREAT NOSE MASS_LO MASS_HI DIAM_LO DIAM_HI [ARGS...]: kg, m
check() {
    name=$1 threat=$2 nose=$3 mlo=$4 mhi=$5 dlo=$6 dhi=$7; shift 7
    dir="$tmp/$name"
    run -tend 1e-5 -threat "$threat" -out "$dir" "$@" > "$dir.log" 2>&1 \
        || { echo "$name: scene exited $?"; tail -3 "$dir.log"; fail=1; return; }
    m=$(num projectile_mass "$dir"); d=$(num projectile_diameter "$dir"); n=$(txt nose "$dir")
    echo "$name: threat $(txt threat "$dir"), nose $n, mass $m kg, diameter $d m, length $(num projectile_length "$dir") m"
    [ "$(txt threat "$dir")" = "$threat" ] || { echo "$name: summary threat '$(txt threat "$dir")'"; fail=1; }
    [ "$n" = "$nose" ] || { echo "$name: nose '$n', want '$nose'"; fail=1; }
    awk -v m="$m" -v a="$mlo" -v b="$mhi" 'BEGIN { exit !(m >= a && m <= b) }' \
        || { echo "$name: mass $m kg not in [$mlo, $mhi]"; fail=1; }
    awk -v d="$d" -v a="$dlo" -v b="$dhi" 'BEGIN { exit !(d >= a && d <= b) }' \
        || { echo "$name: diameter $d m not in [$dlo, $dhi]"; fail=1; }
}
# the specifications' values (tolerances: the specifications' own, or the rounding of a quoted value)
check ball ball hemisphere 0.104 0.104 0.0127 0.0127
check fsp17 fsp17 chisel 1.07e-3 1.13e-3 5.385e-3 5.410e-3        # 17 +- 0.5 grain; MIL-DTL-46593B
check rcc rcc flat 2.5919e-4 2.5920e-4 3.47e-3 3.48e-3              # 4 grain; L/D 1 in steel
check rcc64 rcc64 flat 4.1471e-3 4.1472e-3 8.76e-3 8.77e-3          # 64 grain
check 9mm 9mm hemisphere 8.0e-3 8.0e-3 9.01e-3 9.02e-3              # NIJ 0101.06: 8.0 g; 9.01 mm
check 44mag 44mag flat 15.6e-3 15.6e-3 10.89e-3 10.91e-3            # NIJ 0101.06: 15.6 g; 10.9 mm
check override 9mm flat 0.01 0.01 9.01e-3 9.02e-3 -mass 0.01 -nose flat   # given options win
# a 17-grain FSP at 400 m/s: runs, closes the balance, slows
dir="$tmp/fsp400"
run -threat fsp17 -velocity 400 -tend 3e-5 -out "$dir" > "$dir.log" 2>&1 || { echo "fsp17 400 m/s: exit $?"; tail -3 "$dir.log"; fail=1; }
err=$(num max_energy_error "$dir"); vf=$(num final_projectile_velocity "$dir"); st=$(txt status "$dir")
echo "fsp17 at 400 m/s to 30 us: status $st, final speed $vf m/s, largest energy error $err"
[ "$st" = ok ] || { echo "fsp17: status $st"; fail=1; }
awk -v e="$err" 'BEGIN { exit !(e < 1e-3 && e > -1e-3) }' || { echo "fsp17: energy error $err"; fail=1; }
awk -v v="$vf" 'BEGIN { exit !(v < 400 && v > 0) }' || { echo "fsp17: final speed $vf m/s"; fail=1; }
# obliquity 0 and 30 degrees: the momentum along the path
for theta in 0 30; do
    dir="$tmp/oblique$theta"
    run -threat fsp17 -velocity 400 -obliquity "$theta" -tend 3e-5 -out "$dir" > "$dir.log" 2>&1 \
        || { echo "obliquity $theta: exit $?"; tail -3 "$dir.log"; fail=1; continue; }
    p=$(sed -n 's/^ *"projectile_momentum": \[\(.*\)\].*/\1/p' "$dir/summary.json")
    err=$(num max_energy_error "$dir"); vf=$(num final_projectile_velocity "$dir"); sym=$(num symmetry "$dir")
    m=$(num projectile_mass "$dir")
    echo "obliquity $theta: momentum ($p) kg m/s, final speed $vf m/s, symmetry $sym, energy error $err"
    # (summary.json prints 10 significant digits: 1e-6 deg, 1e-8 of the size)
    echo "$p" | awk -F', *' -v t="$theta" -v m="$m" -v v="$vf" '{
        a = atan2($1, $3) * 45 / atan2(1, 1); size = sqrt($1^2 + $2^2 + $3^2)
        exit !(($2 == 0) && (a - t < 1e-6 && t - a < 1e-6) && (size - m * v < 1e-8 * size && m * v - size < 1e-8 * size)) }' \
        || { echo "obliquity $theta: momentum ($p) not at $theta deg with size m v"; fail=1; }
    awk -v e="$err" 'BEGIN { exit !(e < 1e-3 && e > -1e-3) }' || { echo "obliquity $theta: energy error $err"; fail=1; }
    awk -v v="$vf" 'BEGIN { exit !(v < 400) }' || { echo "obliquity $theta: not slowed ($vf m/s)"; fail=1; }
    want=4; [ "$theta" = 0 ] || want=1
    [ "$sym" = "$want" ] || { echo "obliquity $theta: symmetry $sym, want $want"; fail=1; }
done
# an oblique FSP shot stopped after a checkpoint and restarted: the uninterrupted run's history
o="-threat fsp17 -velocity 300 -obliquity 20 -tend 4e-5"
run $o -checkpoint 2 -stopafter 2 -out "$tmp/ob_cut" > "$tmp/ob_cut.log" 2>&1
[ $? -eq 9 ] || { echo "oblique restart: the first part did not stop after frame 2"; fail=1; }
run $o -checkpoint 2 -restart "$tmp/ob_cut" > "$tmp/ob_rest.log" 2>&1 || { echo "oblique restart: exit $?"; tail -3 "$tmp/ob_rest.log"; fail=1; }
run $o -out "$tmp/ob_whole" > "$tmp/ob_whole.log" 2>&1 || { echo "oblique whole run: exit $?"; fail=1; }
cmp -s "$tmp/ob_cut/history.csv" "$tmp/ob_whole/history.csv" && echo "oblique chisel restarted: the same history.csv" \
    || { echo "oblique restart: history.csv differs from the uninterrupted run's"; fail=1; }
# refusals
bad() {
    want=$1; shift
    run -tend 1e-6 -out "$tmp/bad" "$@" > "$tmp/bad.log" 2>&1
    rc=$?
    [ $rc -eq 2 ] && grep -qF -- "$want" "$tmp/bad.log" || { echo "$*: exit $rc, want 2 and '$want':"; head -3 "$tmp/bad.log"; fail=1; }
    # (nothing written: no folder, or the folder a refusal after the model's build emptied again)
    [ -n "$(ls -A "$tmp/bad" 2>/dev/null)" ] && { echo "$*: wrote results"; fail=1; }
    rm -rf "$tmp/bad"
    grep -m1 '^error' "$tmp/bad.log" | cut -c1-160
}
bad "-threat" -threat fsp64
bad "-obliquity 61: must be in [0, 60]" -obliquity 61
bad "-obliquity 30: the model is a pack of 2 plies" -obliquity 30 -plies 2
bad "-obliquity 30: the model has yarn failure" -obliquity 30 -failure on
[ $fail -eq 0 ] && echo "threats: ok"
exit $fail
