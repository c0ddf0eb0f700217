#!/bin/sh
# The pack study (issue 14, item 4; docs/pack_study.md): V50 and the back-face
# deformation of packs of 1, 2, 4, 8 plies on the coarse mesh, against areal
# density, and Cunniff's dimensionless form (tools/cunniff.sh). Not part of make test.
#
# Usage (repository root, after make):
#   sh bench/pack_study.sh [-plies "1 2 4 8"] [-mesh coarse] [-jobs 2] [-out results/pack_study]
#                          [-args "more ballistic_limit options, e.g. -runs 10 -layup 0"] [-reuse 1]
#                          [-runner local|srun|slurm] [-ranks R]
# Each N: tools/ff.sh freefem_scripts/ballistic_limit.edp -mesh M -plies N -jobs J
#         -overwrite 1 -out OUT/pN $args (the sweep's defaults otherwise: -vmin 10
#         -vmax 100 -runs 16 -tend 10e-3). V50: the fit's (the bracket's when the fit
#         failed or its V_bl sits at the bracket's bound); the back-face deformation (BFD):
#         summary.json "back_face_deformation" of the fastest stopped run (the one nearest
#         the limit that holds), left out when that run's back ply lost elements.
# Writes OUT/study.md (the table), OUT/study.csv (tools/cunniff.sh's columns and the
# fit/bracket V50), OUT/study.png (two panels: V50 and BFD against areal density;
# V50/U*^(1/3) against A_D A_p/m_p), each sweep's files in OUT/pN.
# -reuse 1: a ply count whose OUT/pN/limit.json exists is not run again (its table row
# is read from it: a study in parts); a sweep cut short is taken up again (ballistic_limit
# -resume 1: its finished runs kept) instead of cleared.
# -runner, -ranks: each sweep's (docs/ballistic_limit.md "Runners"): inside an allocation,
#   sbatch -n 16 --wrap "sh bench/pack_study.sh -runner srun -jobs 16"
# Cost (2 cores, -jobs 2): ~2 min for 1 ply, about N times that for N plies.
set -u
plies="1 2 4 8" mesh=coarse jobs=2 out=results/pack_study args="" reuse=0 runner=local ranks=1
while [ $# -gt 0 ]; do
    [ $# -ge 2 ] || { echo "error: pack_study: option $1 needs a value"; exit 2; }
    case "$1" in
        -plies) plies=$2 ;; -mesh) mesh=$2 ;; -jobs) jobs=$2 ;; -out) out=$2 ;; -args) args=$2 ;; -reuse) reuse=$2 ;;
        -runner) runner=$2 ;; -ranks) ranks=$2 ;;
        *) echo "error: pack_study: unknown option '$1' (-plies -mesh -jobs -out -args -reuse -runner -ranks)"; exit 2 ;;
    esac
    shift 2
done
[ -f tools/ff.sh ] || { echo "error: pack_study: run from the repository root"; exit 2; }
for n in $plies; do
    case "$n" in ''|*[!0-9]*) echo "error: pack_study: -plies '$plies': '$n' is not a ply count"; exit 2 ;; esac
done
mkdir -p "$out"
# num FILE KEY [FIELD]: "KEY": {"FIELD": x ...} or "KEY": x
num() {
    if [ $# -eq 3 ]; then sed -n "s/^  \"$2\": {.*\"$3\": \([^,}]*\)[,}].*/\1/p" "$1" | head -1
    else sed -n "s/^  \"$2\": \([^,]*\),*$/\1/p" "$1" | head -1; fi
}
rows="plies,v50,bfd"
table="| plies | areal density (kg/m²) | V50 fit (m/s) | V50 bracket (m/s) | BFD (mm) at (m/s) | runs | wall (s) |
| --- | --- | --- | --- | --- | --- | --- |"
for n in $plies; do
    d="$out/p$n"
    t0=$(date +%s)
    if [ "$reuse" = 1 ] && [ -s "$d/limit.json" ]; then   # (-reuse 1: a sweep already done is read again)
        rc=0 t1=$t0
    else
        fresh="-overwrite 1"   # (-reuse 1: a sweep cut short resumed, its finished runs kept)
        [ "$reuse" = 1 ] && [ -s "$d/runs.txt" ] && fresh="-resume 1"
        # shellcheck disable=SC2086
        sh tools/ff.sh freefem_scripts/ballistic_limit.edp -mesh "$mesh" -plies "$n" -jobs "$jobs" $fresh \
            -runner "$runner" -ranks "$ranks" -out "$d" $args > "$out/p$n.log" 2>&1
        rc=$? t1=$(date +%s)
        echo "$((t1 - t0))" > "$out/p$n.wall"
    fi
    [ -s "$out/p$n.wall" ] && t1=$((t0 + $(cat "$out/p$n.wall")))
    grep -E '^(Lambert|V50|done|error)' "$out/p$n.log" | sed "s/^/$n plies: /"
    j="$d/limit.json"
    if [ ! -s "$j" ]; then
        table="$table
| $n | | failed (exit $rc, $out/p$n.log) | | | | $((t1 - t0)) |"
        continue
    fi
    fit=$(num "$j" v50_fit value) fse=$(num "$j" v50_fit error)
    br=$(num "$j" v50_bracket value) bh=$(num "$j" v50_bracket half_gap)
    runs=$(num "$j" runs_total)
    # the fastest stopped run: its back-face deformation
    best=$(awk -F, 'NR > 1 && $3 == "0" && $4 == "ok" { v = $1; dir = $6 } END { if (v != "") print v "," dir }' "$d/limit.csv")
    bv=${best%%,*} bdir=${best#*,}
    bfd=""
    [ -n "$best" ] && [ -s "$bdir/summary.json" ] && bfd=$(num "$bdir/summary.json" back_face_deformation)
    # a back ply that lost elements has free nodes that fly off: its largest u_z is a
    # fragment's, not the back face's (left out, said in the table)
    lasteroded=$(sed -n 's/^  "ply_eroded": \[\(.*\)\],*$/\1/p' "$bdir/summary.json" 2>/dev/null | awk -F, '{ print $NF + 0 }')
    bfdnote=""
    if [ -n "$bfd" ] && [ "${lasteroded:-0}" -gt 0 ]; then bfdnote="(back ply eroded: $lasteroded elements)"; bfd=""; fi
    if [ -n "$best" ] && [ "$n" -gt 1 ] && [ "$(num "$bdir/summary.json" plies)" != "$n" ]; then
        echo "error: pack_study: $bdir/summary.json has plies '$(num "$bdir/summary.json" plies)', not $n (-plies not passed?)"; exit 1
    fi
    v50=$fit atbound=$(num "$j" v_bl at_bound)
    case "$fit" in ''|null) v50=$br ;; esac
    [ "$atbound" = true ] && v50=$br   # (a fit at the bracket's bound: the bracket's mid-point)
    case "$v50" in ''|null) ;; *) rows="$rows
$n,$v50,$bfd" ;; esac
    row=$(awk -v n="$n" -v f="$fit" -v fs="$fse" -v b="$br" -v bh="$bh" -v bfd="$bfd" -v bv="$bv" -v r="$runs" -v w="$((t1 - t0))" \
              -v ab="$atbound" -v note="$bfdnote" 'BEGIN {
        fs_ = (f == "null" || f == "") ? "no fit" : sprintf("%.2f +- %.2f%s", f, fs, (ab == "true" ? " (at the bracket bound)" : ""))
        bs_ = (b == "null" || b == "") ? "" : sprintf("%.2f +- %.2f", b, bh)
        bf_ = (bfd == "" || bfd == "null") ? note : sprintf("%.1f at %s", 1e3 * bfd, bv)
        printf "| %d | AD | %s | %s | %s | %s | %s |", n, fs_, bs_, bf_, r, w }')
    table="$table
$row"
done
printf '%s\n' "$rows" > "$out/rows.csv"
sh tools/cunniff.sh "$out/rows.csv" > "$out/study.csv" || { echo "error: pack_study: tools/cunniff.sh failed"; exit 1; }
# the areal density into the table (from tools/cunniff.sh: the material's rho_A x plies)
for n in $plies; do
    ad=$(awk -F, -v n="$n" 'NR > 1 && $1 == n { print $2 }' "$out/study.csv")
    table=$(printf '%s\n' "$table" | sed "s/^| $n | AD |/| $n | ${ad:-} |/")
done
ustar=$(sh tools/cunniff.sh -ustar)
{
    echo "# Pack study ($(date -u +%Y-%m-%d), mesh $mesh, plies $plies, -jobs $jobs${args:+, $args})"
    echo
    echo "$table"
    echo
    echo "Cunniff (tools/cunniff.sh): $ustar; A_p = pi (6.35 mm)^2, m_p = 0.104 kg."
    echo
    echo '```'
    cat "$out/study.csv"
    echo '```'
} > "$out/study.md"
cat "$out/study.md"
gnuplot -e "data='$out/study.csv'; out='$out/study.png'" bench/pack_study.gp || echo "warning: pack_study: no study.png (gnuplot failed)"
