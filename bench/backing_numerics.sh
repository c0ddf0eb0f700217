#!/bin/sh
# The bullet on a pack on clay: what the step's numerics cost and change (issue 30;
# docs/backing.md "Speed and accuracy"). One short run of the ballistic scene per
# setting, the same shot: -plies P -backing clay -threat 9mm -velocity 436 -mesh coarse
# to -tend T, and a table of the back-face signature, the pack's back face, the
# projectile's speed at T, the energy error, the steps (and how many the amplitudes'
# travel limit shortened), the smallest step and the wall time. Not part of make test.
#
# Usage (repository root, after make):
#   sh bench/backing_numerics.sh [-plies 24] [-tend 0.1e-3] [-jobs 2] [-out results/backing_numerics]
#                                [-settings "default|-massfactor 10|..."]
# -settings: '|'-separated option sets ("default": none); each run in OUT/runK.
# Writes OUT/table.md. Cost: 24 plies to 0.1 ms, the five default settings ~5 min one at a time.
set -u
plies=24 tend=0.1e-3 jobs=2 out=results/backing_numerics
settings="default|-massfactor 3|-massfactor 10|-travelfraction 0.3|-travel 0"
while [ $# -gt 0 ]; do
    case "$1" in
        -plies) plies=$2; shift 2 ;;
        -tend) tend=$2; shift 2 ;;
        -jobs) jobs=$2; shift 2 ;;
        -out) out=$2; shift 2 ;;
        -settings) settings=$2; shift 2 ;;
        *) echo "error: backing_numerics: unknown option '$1' (-plies -tend -jobs -out -settings)"; exit 2 ;;
    esac
done
[ -f tools/ff.sh ] || { echo "error: backing_numerics: run from the repository root"; exit 2; }
mkdir -p "$out" || exit 2
# one run: index, options
one() {
    k=$1; shift
    start=$(date +%s.%N)
    sh tools/ff.sh freefem_scripts/ballistic_impact.edp -plies "$plies" -backing clay -threat 9mm \
        -velocity 436 -mesh coarse -tend "$tend" -plots 0 -settle 0 -overwrite 1 -out "$out/run$k" "$@" \
        > "$out/run$k.log" 2>&1
    echo "$? $(date +%s.%N) $start" > "$out/run$k.rc"
}
n=0
IFS='|'
for s in $settings; do n=$((n + 1)); echo "$s" > "$out/run$n.set"; done
unset IFS
k=1 running=0
while [ $k -le $n ]; do
    s=$(cat "$out/run$k.set")
    [ "$s" = default ] && s=""
    # shellcheck disable=SC2086
    one $k $s &
    running=$((running + 1)); k=$((k + 1))
    if [ $running -ge "$jobs" ]; then wait; running=0; fi
done
wait
key() { sed -n "s/^ *\"$2\": \([^,]*\),*$/\1/p" "$out/run$1/summary.json" | head -1; }
{
    echo "| setting | BFS (mm) | back face (mm) | projectile at $tend s (m/s) | largest energy error | steps (travel-limited) | smallest step (s) | wall (s) |"
    echo "|---|---|---|---|---|---|---|---|"
    k=1
    while [ $k -le $n ]; do
        set -- $(cat "$out/run$k.rc")
        if [ "$1" != 0 ] || [ ! -f "$out/run$k/summary.json" ]; then
            echo "| $(cat "$out/run$k.set") | failed (exit $1: $out/run$k.log) | | | | | | |"
        else
            awk -v s="$(cat "$out/run$k.set")" -v bfs="$(key $k backface_signature)" -v bf="$(key $k back_face_deformation)" \
                -v v="$(key $k final_projectile_velocity)" -v e="$(key $k max_energy_error)" -v st="$(key $k steps)" \
                -v tr="$(key $k travel_steps)" -v dt="$(key $k dt_min)" -v w0="$3" -v w1="$2" 'BEGIN {
                printf "| %s | %.2f | %s | %.1f | %.3f %% | %d (%d) | %.3g | %.0f |\n", s, bfs * 1e3,
                    (bf == "" || bf == "null") ? "-" : sprintf("%.2f", bf * 1e3), v, e * 100, st, tr, dt, w1 - w0 }'
        fi
        k=$((k + 1))
    done
} > "$out/table.md"
cat "$out/table.md"
