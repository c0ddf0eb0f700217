#!/bin/sh
# Bad input reaches the scene user as one clear line, with a documented exit
# code (docs/limits.md, "Errors"):
#   2  a bad option: unknown, without its value, given twice, not a number,
#      out of range (named, with what is allowed)
#   3  a results folder that cannot be written
#   4  the run failed (mesh file missing or corrupt, a group the mesh lacks,
#      an unstable step...): summary.json says "status": "failed" and why,
#      and the history written so far stays
# for the ballistic scene (and the strip scene for options and a failed run).
set -u
tmp="${WFF_TEST_TMP:-/tmp}/bad_input"
rm -rf "$tmp"
mkdir -p "$tmp"
fail=0
ballistic=freefem_scripts/ballistic_impact.edp
strip=freefem_scripts/strip_tension.edp

# expect NAME SCRIPT STATUS PATTERN... -- ARGS: want exit STATUS and every
# PATTERN (fixed string) in the output; for status 4 also in summary.json
expect() {
    name=$1; script=$2; want=$3; shift 3
    patterns=""
    while [ "$1" != "--" ]; do patterns="$patterns$1
"; shift; done
    shift
    out="$tmp/$name"
    outarg="-out $out"   # unless the case gives its own -out
    for a in "$@"; do [ "$a" = "-out" ] && outarg=""; done
    sh tools/ff.sh "$script" -plots 0 $outarg "$@" > "$out.log" 2>&1
    rc=$?
    ok=1
    [ "$rc" -eq "$want" ] || { echo "$name: exit $rc, want $want"; ok=0; }
    printf '%s' "$patterns" | while IFS= read -r p; do
        grep -qF -- "$p" "$out.log" || { echo "$name: output lacks '$p'"; exit 1; }
        if [ "$want" -eq 4 ]; then
            grep -qF -- "$(printf '%s' "$p" | sed 's/"/\\"/g')" "$out/summary.json" 2>/dev/null \
                || { echo "$name: summary.json lacks '$p'"; exit 1; }
        fi
    done || ok=0
    if [ "$want" -eq 4 ]; then
        grep -q '"status": "failed"' "$out/summary.json" 2>/dev/null \
            || { echo "$name: summary.json does not say failed"; ok=0; }
    fi
    if [ "$want" -ne 4 ] && [ -f "$out/summary.json" ]; then
        echo "$name: a summary.json was written"; ok=0
    fi
    if [ $ok -eq 0 ]; then sed 's/^/    | /' "$out.log" | tail -8; fail=1; fi
    grep -m1 '^error: ' "$out.log" | cut -c1-200 | sed "s/^/  $name: /"
}

short="-mesh coarse -tend 2e-5"
expect unknown_option "$ballistic" 2 "unknown option '-xyz'" "known options: -out -material -mesh" \
    -- $short -xyz 3
expect stray_argument "$ballistic" 2 "unexpected argument 'coarse'" -- -tend 2e-5 coarse
expect not_a_number "$ballistic" 2 "-velocity 'fast' is not a number" -- $short -velocity fast
expect negative_speed "$ballistic" 2 "error: ballistic_impact: -velocity -1: must be >= 0 (impact speed, toward +z, m/s)" \
    -- $short -velocity -1
expect negative_mass "$ballistic" 2 "-mass -0.1: must be > 0 (projectile mass, whole, kg)" -- $short -mass -0.1
expect inside_fabric "$ballistic" 2 \
    "-standoff -0.001: must be >= 0 (gap between the nose tip and the fabric at t = 0, m)" \
    -- $short -standoff -0.001
expect bad_dtfactor "$ballistic" 2 "-dtfactor 3: must be in (0, 2]" -- $short -dtfactor 3
expect bad_clamp "$ballistic" 2 "-clamp 'glue': must be one of fixed|friction" -- $short -clamp glue
expect missing_value "$ballistic" 2 "error: ballistic_impact: option -velocity needs a value" -- $short -velocity
expect value_is_option "$ballistic" 2 "option -mesh needs a value, not the option -tend" -- -mesh -tend 2e-5
expect duplicate "$ballistic" 2 "option -tend given twice ('2e-5' and '1e-5')" -- $short -tend 1e-5
expect not_whole "$ballistic" 2 "-checkpoint 1.5 is not a whole number" -- $short -checkpoint 1.5
expect bad_elements "$ballistic" 2 "-elements 'hex': must be one of tri|quad" -- $short -elements hex
expect help "$ballistic" 0 "-velocity       22" "real>=0: impact speed" -- -help
expect unwritable_out "$ballistic" 3 "output folder '/proc/wovenff_forbidden' cannot be created or written" \
    -- $short -out /proc/wovenff_forbidden
expect missing_mesh "$ballistic" 4 "wovenffModel: $tmp/none.msh: cannot read: No such file or directory" \
    -- -tend 2e-5 -mesh "$tmp/none.msh"
printf '$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\ngarbage\n' > "$tmp/corrupt.msh"
expect corrupt_mesh "$ballistic" 4 "wovenffModel: $tmp/corrupt.msh:" -- -tend 2e-5 -mesh "$tmp/corrupt.msh"
expect missing_group "$ballistic" 4 "wovenffFix: no physical group named 'clamp' in the mesh (groups: sym_x, sym_y, rim, fabric)" \
    -- -tend 2e-5 -mesh tests/data/quarter_no_clamp.geo
expect unstable "$ballistic" 4 "wovenffAdvance: t = " "unstable (time step" "1.5 x the stable estimate" \
    "at triangle " "suggested -dtfactor 0.8" -- -mesh coarse -tend 1e-4 -dtfactor 1.5 -travel 0
# the history up to the failure stays, complete rows only
awk -F, 'NR == 1 { n = NF } NR > 1 && NF != n { bad = 1 } END { exit !(NR >= 2 && !bad) }' \
    "$tmp/unstable/history.csv" || { echo "unstable: history.csv not kept whole"; fail=1; }
grep -q '"steps": [1-9]' "$tmp/unstable/summary.json" || { echo "unstable: summary lacks the step"; fail=1; }

expect strip_unknown "$strip" 2 "strip_tension: unknown option '-tend'" -- -tend 1
expect strip_negative "$strip" 2 "error: strip_tension: -velocity -2: must be > 0 (grip speed, m/s)" -- -velocity -2
expect clampmu_fixed "$ballistic" 2 "are settings of -clamp friction" -- $short -clampmu 0.2
expect plates_too_big "$ballistic" 2 "-plates 0.3: must be 0 or between the opening radius" -- $short -plates 0.3
expect staples_alone "$ballistic" 2 "-staples 1 needs -plates S" -- $short -staples 1
expect clampforce_negative "$ballistic" 2 "-clampforce -5: must be > 0" -- $short -clamp friction -clampforce -5
expect strip_not_a_number "$strip" 2 "error: strip_tension: -strain '4%' is not a number" -- -strain 4%
expect strip_missing_value "$strip" 2 "error: strip_tension: option -family needs a value" -- -strain 0.003 -family
expect strip_bad_family "$strip" 2 "-family 'wrap': must be one of warp|weft|both" -- -family wrap
expect strip_missing_mesh "$strip" 4 "wovenffModel: $tmp/none.msh: cannot read" -- -mesh "$tmp/none.msh"
expect strip_unstable "$strip" 4 "unstable (time step" "at quadrilateral " "suggested -dtfactor 0.8" \
    -- -strain 0.003 -dtfactor 1.5
exit $fail
