#!/bin/sh
# Bad input reaches the scene user as one clear line, with a documented exit
# code (docs/limits.md, "Errors"):
#   2  a bad option: unknown, not a number, out of range (named)
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
    sh tools/ff.sh "$script" -plots 0 -out "$out" "$@" > "$out.log" 2>&1
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
expect negative_speed "$ballistic" 2 "-velocity -1: the impact speed must be >= 0 m/s" -- $short -velocity -1
expect negative_mass "$ballistic" 2 "-mass -0.1: the projectile mass must be > 0 kg" -- $short -mass -0.1
expect inside_fabric "$ballistic" 2 "-standoff -0.001: the projectile would start inside the fabric" \
    -- $short -standoff -0.001
expect bad_dtfactor "$ballistic" 2 "-dtfactor 3: must be in (0, 2]" -- $short -dtfactor 3
expect bad_clamp "$ballistic" 2 "-clamp must be 'fixed' or 'friction', got 'glue'" -- $short -clamp glue
expect unwritable_out "$ballistic" 3 "output folder '/proc/wovenff_forbidden' cannot be created or written" \
    -- $short -out /proc/wovenff_forbidden
expect missing_mesh "$ballistic" 4 "wovenffModel: $tmp/none.msh: cannot read: No such file or directory" \
    -- -tend 2e-5 -mesh "$tmp/none.msh"
printf '$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\ngarbage\n' > "$tmp/corrupt.msh"
expect corrupt_mesh "$ballistic" 4 "wovenffModel: $tmp/corrupt.msh:" -- -tend 2e-5 -mesh "$tmp/corrupt.msh"
expect missing_group "$ballistic" 4 "wovenffFix: no physical group named 'clamp' in the mesh (groups: sym_x, sym_y, rim, fabric)" \
    -- -tend 2e-5 -mesh tests/data/quarter_no_clamp.geo
expect unstable "$ballistic" 4 "wovenffAdvance: t = " "unstable (time step" "1.5 x the stable estimate" \
    "at triangle " "suggested -dtfactor 0.8" -- -mesh coarse -tend 1e-4 -dtfactor 1.5
# the history up to the failure stays, complete rows only
awk -F, 'NR == 1 { n = NF } NR > 1 && NF != n { bad = 1 } END { exit !(NR >= 2 && !bad) }' \
    "$tmp/unstable/history.csv" || { echo "unstable: history.csv not kept whole"; fail=1; }
grep -q '"steps": [1-9]' "$tmp/unstable/summary.json" || { echo "unstable: summary lacks the step"; fail=1; }

expect strip_unknown "$strip" 2 "strip_tension: unknown option '-tend'" -- -tend 1
expect strip_negative "$strip" 2 "-velocity -2: the grip speed must be > 0 m/s" -- -velocity -2
expect strip_missing_mesh "$strip" 4 "wovenffModel: $tmp/none.msh: cannot read" -- -mesh "$tmp/none.msh"
expect strip_unstable "$strip" 4 "unstable (time step" "at quadrilateral " "suggested -dtfactor 0.8" \
    -- -strain 0.003 -dtfactor 1.5
exit $fail
