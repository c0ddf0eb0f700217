#!/bin/sh
# The ballistic scene's -failure on|off (issue 13; docs/limits.md "Perforation").
# Refusals, each exit 2 with one line naming the option and the file, and no
# summary.json: -failure on with a material file without failure data, with a
# cell that cannot fail or failure data it refuses, with -adapt, -zonal or
# -amplitudes static; a negative crack band (-set failure_band_length=-1e-3);
# -erosion without -failure on. Then (the Kevlar file
# holding failure data) the paper's 22 m/s on the coarse mesh: with failure off
# the largest yarn strain passes the rupture strain under the nose, and with
# failure on the projectile perforates (the model's prediction; the experiment
# did not perforate: docs/penetration.md); fast, it perforates: perforated
# true, a residual speed > 0 and below the impact speed, eroded elements,
# failure energy > 0, the energy balance within 1 % of the impact energy, the
# history's failure columns, damage.png, the damage fields in the VTK frames;
# a run stopped after elements eroded and restarted from its checkpoint ends as the
# uninterrupted one. With the friction clamp at the seed's force (the default,
# 116 kN over the specimen: 29 kN on the quarter model) 22 m/s perforates too;
# with a quarter of it (29 kN over the specimen) the ply slips and nothing fails.
# (-failure off, the paper's scene unchanged: sh/ballistic_scene.sh, make run.)
set -u
tmp="${WFF_TEST_TMP:-/tmp}/failure_scene"
rm -rf "$tmp"; mkdir -p "$tmp"
fail=0
scene=freefem_scripts/ballistic_impact.edp
kevlar=freefem_scripts/materials/kevlar_s706.txt
short="-mesh coarse -tend 2e-5 -plots 0"

# refuse NAME PATTERN... -- ARGS: exit 2, every PATTERN (fixed string) in the
# output, no summary.json
refuse() {
    name=$1; shift
    patterns=""
    while [ "$1" != "--" ]; do patterns="$patterns$1
"; shift; done
    shift
    out="$tmp/$name"
    sh tools/ff.sh "$scene" -out "$out" "$@" > "$out.log" 2>&1
    rc=$?
    ok=1
    [ $rc -eq 2 ] || { echo "$name: exit $rc, want 2"; ok=0; }
    printf '%s' "$patterns" | while IFS= read -r p; do
        grep -qF -- "$p" "$out.log" || { echo "$name: output lacks '$p'"; exit 1; }
    done || ok=0
    [ -f "$out/summary.json" ] && { echo "$name: a summary.json was written"; ok=0; }
    if [ $ok -eq 0 ]; then sed 's/^/    | /' "$out.log" | tail -6; fail=1; fi
    grep -m1 '^error: ' "$out.log" | cut -c1-220 | sed "s/^/  $name: /"
}

refuse no_failure_data "error: ballistic_impact: -failure on: the material file tests/data/king_symmetric.txt holds no failure data" \
    "fail_strain_1" -- $short -failure on -material tests/data/king_symmetric.txt
# the linear and basket cells with failure keys added, the rupture strain below
# the failure strain: refused either way (no failure in the cell, or the order)
for cell in linear basket; do
    grep -v '^ *\(failure\|fail_strain\|rupture_strain\)' "freefem_scripts/materials/kevlar_$cell.txt" > "$tmp/$cell.txt"
    printf 'failure = 0\nfail_strain_1 = 0.04\nfail_strain_2 = 0.04\nrupture_strain_1 = 0.03\nrupture_strain_2 = 0.03\n' \
        >> "$tmp/$cell.txt"
    refuse "${cell}_refused" "error: ballistic_impact: -failure on: the material file $tmp/$cell.txt cannot fail: wovenffMaterialOverride:" \
        -- $short -failure on -material "$tmp/$cell.txt"
    [ -d "$tmp/${cell}_refused" ] && [ "$(ls -A "$tmp/${cell}_refused")" != "" ] \
        && { echo "${cell}_refused: the refused run left files in its folder"; fail=1; }
done
# (what -failure on cannot go with, the model answers: plugin/combine.c, wovenffRefuses)
refuse with_adapt "-adapt 5: the model has yarn failure with erosion on" \
    "a mesh transfer does not carry the eroded elements" "(the model: -failure on)" -- $short -failure on -adapt 5
refuse with_zonal "-zonal 0.05: the model has yarn failure with erosion on" "would never break" \
    "(the model: -failure on)" -- $short -failure on -zonal 0.05
refuse with_static "-amplitudes static: the model has yarn failure with erosion on" \
    "(the model: -failure on)" -- $short -failure on -amplitudes static
refuse band_negative "key 'failure_band_length' = -1e-3: must be >= 0 m" -- $short -failure on \
    -set failure_band_length=-1e-3
refuse erosion_alone "-erosion either is a setting of -failure on" -- $short -erosion either
refuse bad_choice "-failure 'yes': must be one of on|off" -- $short -failure yes

if ! grep -q '^ *failure *=' "$kevlar" || [ ! -f plugin/erosion.c ]; then   # (until both are in the core)
    echo "perforation runs not made: the failure data ($kevlar) or the erosion (plugin/erosion.c) is not in the core yet (the refusals above were checked)"
    exit $fail
fi

# num FILE KEY: a number (or true/false/null) from summary.json
num() { sed -n "s/^  \"$2\": \([^,]*\),*$/\1/p" "$1/summary.json"; }

# 22 m/s, the paper's speed. The model as parametrised breaks the yarns there
# (docs/penetration.md "The paper's 22 m/s shot"; the experiment did not
# perforate): with failure off the largest yarn strain T_k/(k_k L0_k) of the
# run, under the nose, passes the rupture strain (coarse 5.49 %, default 5.00 %,
# fine 5.59 %; 4.52 % in the file), and with failure on the projectile
# perforates with the energy balance within 1 %.
rupture=$(sed -n 's/^rupture_strain_1 *= *\([0-9.eE+-]*\).*/\1/p' "$kevlar")
out="$tmp/slow_off"
sh tools/ff.sh tests/tools/yarn_strain_probe.edp -mesh coarse -tend 2e-3 -every 1000 -threads 1 \
    -out "$out" > "$out.log" 2>&1
rc=$?
peak=$(grep '^probe peak' "$out.log")
echo "$peak" | cut -c1-200
if [ $rc -ne 0 ] || [ -z "$peak" ]; then echo "slow_off: exit $rc"; sed 's/^/    | /' "$out.log" | tail -6; fail=1
else
    echo "$peak" | awk -v r="$rupture" '{
        e1 = $4 / 100; r1 = $8 / 1000; e2 = $18 / 100; r2 = $22 / 1000
        e = e1 > e2 ? e1 : e2; at = e1 > e2 ? r1 : r2
        if (!(r > 0)) { print "slow_off: no rupture_strain_1 in the material file"; exit 1 }
        if (!(e > r)) { print "slow_off: largest yarn strain " e " not above the rupture strain " r; exit 1 }
        if (!(at < 6.35e-3)) { print "slow_off: the largest strain at r = " at " m, not under the nose"; exit 1 }
    }' || fail=1
fi
out="$tmp/slow"
sh tools/ff.sh "$scene" -mesh coarse -plots 0 -vtkdt 1e-3 -failure on -out "$out" > "$out.log" 2>&1
rc=$?
tail -2 "$out.log"
if [ $rc -ne 0 ]; then echo "slow: exit $rc"; sed 's/^/    | /' "$out.log" | tail -6; fail=1
else
    [ "$(num "$out" perforated)" = true ] || { echo "slow: not perforated at 22 m/s (the failure-off strain passes rupture)"; fail=1; }
    awk -v r="$(num "$out" residual_velocity)" -v e="$(num "$out" eroded_elements)" \
        -v err="$(num "$out" max_energy_error)" 'BEGIN {
        if (!(r > 0 && r < 22)) { print "slow: residual velocity " r " not in (0, 22)"; bad = 1 }
        if (!(e > 0)) { print "slow: no element eroded"; bad = 1 }
        if (!(err <= 0.01)) { print "slow: energy error " err " above 1 %"; bad = 1 }
        exit bad }' || fail=1
fi

# 22 m/s with the friction clamp at 29 kN over the whole specimen (-clampforce
# 29e3, a quarter of the default: the ply slips 7 mm in it): no element erodes,
# no yarn is damaged, the projectile turns back (coarse: at 2.80 ms, failure
# energy 0): the fixed clamp's perforation above is the clamp's doing
# (docs/penetration.md, docs/clamp.md).
out="$tmp/slow_clamp"
sh tools/ff.sh "$scene" -mesh coarse -plots 0 -vtkdt 1e-3 -tend 3.5e-3 -failure on -clamp friction \
    -clampforce 29e3 -out "$out" > "$out.log" 2>&1
rc=$?
if [ $rc -ne 0 ]; then echo "slow_clamp: exit $rc"; sed 's/^/    | /' "$out.log" | tail -6; fail=1
else
    [ "$(num "$out" perforated)" = false ] || { echo "slow_clamp: perforated at 22 m/s with the friction clamp at 29 kN"; fail=1; }
    back=$(awk -F, 'NR > 1 && $4 <= 0 { print $1; exit }' "$out/history.csv")
    echo "slow_clamp: eroded $(num "$out" eroded_elements), failure energy $(num "$out" failure_energy) J, turned back at ${back:-never} s"
    awk -v e="$(num "$out" eroded_elements)" -v w="$(num "$out" failure_energy)" -v b="$back" \
        -v err="$(num "$out" max_energy_error)" 'BEGIN {
        if (e != 0) { print "slow_clamp: " e " elements eroded"; bad = 1 }
        if (!(w == 0)) { print "slow_clamp: failure energy " w " J (a yarn was damaged)"; bad = 1 }
        if (b == "") { print "slow_clamp: the projectile did not turn back by 3.5 ms"; bad = 1 }
        if (!(err <= 0.01)) { print "slow_clamp: energy error " err " above 1 %"; bad = 1 }
        exit bad }' || fail=1
fi

# 22 m/s with the friction clamp at its default, the seed's force (116 kN over
# the specimen, 29 kN on the quarter model; the ply slips < 1 mm by then): it
# perforates as with the fixed clamp (coarse: at 1.52 ms, residual 14.1 m/s,
# 3 elements eroded), which the experiment did not (docs/clamp.md).
out="$tmp/slow_seed_clamp"
sh tools/ff.sh "$scene" -mesh coarse -plots 0 -vtkdt 1e-3 -tend 3.5e-3 -failure on -clamp friction \
    -out "$out" > "$out.log" 2>&1
rc=$?
tail -2 "$out.log"
if [ $rc -ne 0 ]; then echo "slow_seed_clamp: exit $rc"; sed 's/^/    | /' "$out.log" | tail -6; fail=1
else
    [ "$(num "$out" perforated)" = true ] || { echo "slow_seed_clamp: not perforated at 22 m/s with the default friction clamp"; fail=1; }
    awk -v r="$(num "$out" residual_velocity)" -v e="$(num "$out" eroded_elements)" \
        -v err="$(num "$out" max_energy_error)" 'BEGIN {
        if (!(r > 0 && r < 22)) { print "slow_seed_clamp: residual velocity " r " not in (0, 22)"; bad = 1 }
        if (!(e > 0)) { print "slow_seed_clamp: no element eroded"; bad = 1 }
        if (!(err <= 0.01)) { print "slow_seed_clamp: energy error " err " above 1 %"; bad = 1 }
        exit bad }' || fail=1
fi

# fast (the done-means speed): perforates
v=300
out="$tmp/fast"
sh tools/ff.sh "$scene" -mesh coarse -tend 1e-3 -velocity $v -vtkdt 5e-5 -failure on -out "$out" > "$out.log" 2>&1
rc=$?
tail -3 "$out.log"
if [ $rc -ne 0 ]; then echo "fast: exit $rc"; sed 's/^/    | /' "$out.log" | tail -6; fail=1
else
    [ "$(num "$out" perforated)" = true ] || { echo "fast: not perforated at $v m/s"; fail=1; }
    awk -v r="$(num "$out" residual_velocity)" -v v=$v -v e="$(num "$out" eroded_elements)" \
        -v w="$(num "$out" failure_energy)" -v err="$(num "$out" max_energy_error)" 'BEGIN {
        if (!(r > 0 && r < v)) { print "fast: residual velocity " r " not in (0, " v ")"; bad = 1 }
        if (!(e > 0)) { print "fast: no element eroded"; bad = 1 }
        if (!(w > 0)) { print "fast: failure energy " w " J"; bad = 1 }
        if (!(err <= 0.01)) { print "fast: energy error " err " above 1 %"; bad = 1 }
        exit bad }' || fail=1
    grep -q '"failure_end": "perforated"' "$out/summary.json" || { echo "fast: failure_end not perforated"; fail=1; }
    for col in failure_energy eroded_energy; do
        head -1 "$out/history.csv" | tr ',' '\n' | grep -qx "$col" || { echo "fast: history.csv lacks $col"; fail=1; }
    done
    [ -s "$out/damage.png" ] || { echo "fast: no damage.png"; fail=1; }
    last=$(ls "$out"/vtk/frame_*.vtu | sort -t_ -k2 -n | tail -1)
    for f in damage1 damage2 eroded; do
        grep -q "Name=\"$f\"" "$last" || { echo "fast: $last lacks $f"; fail=1; }
    done
    # the run ended at perforation, before -tend
    awk -F, 'NR > 1 { t = $1 } END { exit !(t < 0.99e-3) }' "$out/history.csv" \
        || { echo "fast: the run went on to -tend after perforating"; fail=1; }
fi
# a -failure on run checkpointed after elements have eroded, stopped (as a crash
# would) and restarted ends as the uninterrupted run: the same history rows
# (damage, erosion, failure and eroded energies carried), the same perforation keys
whole="$tmp/whole"; part="$tmp/part"
args="-mesh coarse -plots 0 -velocity 300 -failure on -threads 1 -vtkdt 1"
sh tools/ff.sh "$scene" $args -out "$whole" > "$whole.log" 2>&1
rc1=$?
sh tools/ff.sh "$scene" $args -out "$part" -checkpoint 1 -stopafter 5 > "$part.log" 2>&1
rc2=$?
sh tools/ff.sh "$scene" $args -restart "$part" > "$part.restart.log" 2>&1
rc3=$?
if [ $rc1 -ne 0 ] || [ $rc2 -ne 9 ] || [ $rc3 -ne 0 ]; then
    echo "restart: exits $rc1 (whole), $rc2 (stopped, want 9), $rc3 (restarted)"; tail -3 "$part.restart.log"; fail=1
else
    eroded5=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "eroded_energy") c = i } NR == 7 { print $c }' "$whole/history.csv")
    awk -v e="$eroded5" 'BEGIN { exit !(e > 0) }' || echo "restart: nothing eroded by frame 5 (eroded energy '$eroded5' J): the restart carries damage only"
    cmp -s "$whole/history.csv" "$part/history.csv" || { echo "restart: history.csv differs from the uninterrupted run's"; fail=1; }
    for key in perforated residual_velocity perforation_time eroded_elements failure_energy eroded_energy; do
        a=$(num "$whole" $key); b=$(num "$part" $key)
        [ -n "$a" ] && [ "$a" = "$b" ] || { echo "restart: $key '$b', uninterrupted '$a'"; fail=1; }
    done
fi
exit $fail
