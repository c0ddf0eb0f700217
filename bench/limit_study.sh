#!/bin/sh
# The ballistic-limit study (issue 13, item 7; docs/penetration.md "The ballistic
# limit of the paper's ply"): V50 of the paper's scene with -failure on, on several
# meshes, beside the Phoenix-Porwal membrane estimate. Not part of make test.
#
# Usage (repository root, after make):
#   sh bench/limit_study.sh [-meshes "coarse default"] [-jobs 2] [-out results/limit_study]
#                           [-args "more ballistic_limit options"] [-set "key=value,..."]
# Each mesh: tools/ff.sh freefem_scripts/ballistic_limit.edp -mesh M -jobs J
#            -out OUT/M $args  (the sweep's defaults otherwise: -vmin 10 -vmax 100
#            -runs 16 -tend 10e-3), then a table (markdown) of V50 from the fit and
#            from the bracket, the Lambert-Jonas constants, the runs and the wall
#            time, and the Phoenix-Porwal V50 (tools/phoenix_porwal.sh) with the
#            ratio. Writes OUT/study.md; each sweep's files in OUT/M. -set: material
#            values for every run (the scene's -set, through the sweep's -base; the spot
#            runs too), e.g. -set failure_band_length=1.55e-3 (docs/penetration.md).
#   sh bench/limit_study.sh -meshes "" -spot fine -speeds "15.56 16.67"
#            single runs on mesh -spot at each speed (-tend 6e-3, 2 at once), the outcome
#            from the history: perforated (summary), turned back (the projectile's
#            velocity reached 0), or still moving on at the end; written to OUT/spot.md.
#            The fine mesh's check of the coarse/default bracket (a whole fine sweep is
#            too slow: ~30 s CPU per ms of a run).
# Cost (2 cores shared by others, -jobs 2): coarse ~2 min, default ~9 min (5 CPU min);
# the spot check on fine ~10 min.
set -u
meshes="coarse default" jobs=2 out=results/limit_study args="" spot="" speeds="" set=""
while [ $# -gt 0 ]; do
    case "$1" in
        -meshes) meshes=$2; shift 2 ;;
        -jobs) jobs=$2; shift 2 ;;
        -out) out=$2; shift 2 ;;
        -args) args=$2; shift 2 ;;
        -spot) spot=$2; shift 2 ;;
        -speeds) speeds=$2; shift 2 ;;
        -set) set=$2; shift 2 ;;
        *) echo "error: limit_study: unknown option '$1' (-meshes -jobs -out -args -spot -speeds -set)"; exit 2 ;;
    esac
done
case "$set" in *" "*) echo "error: limit_study: -set '$set': no blanks (key=value,key=value)"; exit 2 ;; esac
[ -f tools/ff.sh ] || { echo "error: limit_study: run from the repository root"; exit 2; }
mkdir -p "$out"
# num FILE KEY [FIELD]: "KEY": {"FIELD": x ...} or "KEY": x
num() {
    if [ $# -eq 3 ]; then sed -n "s/^  \"$2\": {.*\"$3\": \([^,}]*\)[,}].*/\1/p" "$1" | head -1
    else sed -n "s/^  \"$2\": \([^,]*\),*$/\1/p" "$1" | head -1; fi
}
pp=$(sh tools/phoenix_porwal.sh | sed -n 's/^V50 *\([0-9.]*\) m\/s.*/\1/p')
ppclamp=$(sh tools/phoenix_porwal.sh | sed -n 's/.*above \([0-9.]*\) m\/s.*/\1/p')
table="| mesh | elements | V50 fit (m/s) | V50 bracket (m/s) | V_bl, a, p | runs | wall (s) | Phoenix-Porwal (m/s) | fit / P-P |
| --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for m in $meshes; do
    d="$out/$m"
    t0=$(date +%s)
    # shellcheck disable=SC2086
    sh tools/ff.sh freefem_scripts/ballistic_limit.edp -mesh "$m" -jobs "$jobs" -overwrite 1 -out "$d" $args \
        ${set:+-base "-set $set"} > "$out/$m.log" 2>&1
    rc=$? t1=$(date +%s)
    grep -E '^(Lambert|V50|done|error)' "$out/$m.log" | sed "s/^/$m: /"
    j="$d/limit.json"
    if [ $rc -ne 0 ] || [ ! -s "$j" ]; then
        table="$table
| $m | | failed (exit $rc, $out/$m.log) | | | | $((t1 - t0)) | $pp | |"
        continue
    fi
    first=$(ls -d "$d"/v* | head -1)
    elems=$(sed -n 's/^  "elements": \([0-9]*\),*$/\1/p' "$first/summary.json" | head -1)
    fit=$(num "$j" v50_fit value) fse=$(num "$j" v50_fit error)
    br=$(num "$j" v50_bracket value) bh=$(num "$j" v50_bracket half_gap)
    vbl=$(num "$j" v_bl value) a=$(num "$j" a value) ase=$(num "$j" a std_error)
    p=$(num "$j" p value) pse=$(num "$j" p std_error) bound=$(num "$j" v_bl at_bound)
    runs=$(num "$j" runs_total) und=$(num "$j" runs_undecided)
    row=$(awk -v f="$fit" -v fs="$fse" -v b="$br" -v bh="$bh" -v vbl="$vbl" -v a="$a" -v as="$ase" \
              -v p="$p" -v ps="$pse" -v pp="$pp" -v bd="$bound" 'BEGIN {
        printf "%.2f +- %.2f%s | %.2f +- %.2f | %.2f, %.3f +- %.3f, %.2f +- %.2f | ", f, fs, (bd == "true" ? " (at the bracket bound)" : ""), b, bh, vbl, a, as, p, ps
        printf "RUNS | WALL | %.1f | %.3f", pp, f / pp }')
    row=$(echo "$row" | sed "s/RUNS/$runs (${und:-0} undecided)/; s/WALL/$((t1 - t0))/")
    table="$table
| $m | $elems | $row |"
done
{
    echo "# Ballistic-limit study ($(date -u +%Y-%m-%d), meshes: $meshes, -jobs $jobs${args:+, $args}${set:+, -set $set})"
    echo
    echo "$table"
    echo
    echo "Phoenix-Porwal (tools/phoenix_porwal.sh): infinite membrane $pp m/s; the paper's clamp reached before"
    echo "the strain peaks: failure before the cone reaches it above $ppclamp m/s."
} > "$out/study.md"
cat "$out/study.md"

# the spot check: single runs on mesh $spot
if [ -n "$spot" ] && [ -n "$speeds" ]; then
    for v in $speeds; do
        sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh "$spot" -plots 0 -vtkdt 1 -failure on \
            -velocity "$v" -threads 1 -tend 6e-3 -overwrite 1 -out "$out/spot_$spot/v$v" ${set:+-set "$set"} \
            > "$out/spot_$spot.v$v.log" 2>&1 &
    done
    wait
    {
        echo "| mesh | V_s (m/s) | outcome | at (ms) | projectile at the end (m/s) | eroded | failure energy (J) | max energy error |"
        echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
        for v in $speeds; do
            d="$out/spot_$spot/v$v"
            [ -s "$d/summary.json" ] || { echo "| $spot | $v | failed ($out/spot_$spot.v$v.log) | | | | | |"; continue; }
            perf=$(num "$d/summary.json" perforated) pt=$(num "$d/summary.json" perforation_time)
            back=$(awk -F, 'NR > 1 && $4 <= 0 { print $1; exit }' "$d/history.csv")
            vend=$(num "$d/summary.json" final_projectile_velocity)
            if [ "$perf" = true ]; then what=perforated at=$pt
            elif [ -n "$back" ]; then what="turned back" at=$back
            else what="still moving on at -tend" at=""; fi
            awk -v m="$spot" -v v="$v" -v w="$what" -v at="$at" -v ve="$vend" -v e="$(num "$d/summary.json" eroded_elements)" \
                -v f="$(num "$d/summary.json" failure_energy)" -v err="$(num "$d/summary.json" max_energy_error)" \
                'BEGIN { printf "| %s | %s | %s | %s | %.3g | %s | %.3g | %.3g %% |\n", m, v, w, (at == "" ? "" : sprintf("%.3f", 1e3 * at)), ve, e, f, 100 * err }'
        done
    } > "$out/spot.md"
    cat "$out/spot.md"
fi
