#!/bin/sh
# make bench: what wovenff's knobs cost and what they buy. Not part of make test.
#   1. kernel speed: ns per element-step of the King step on tri3 and quad4 at
#      ~5k, ~50k and ~500k elements, 1 and 2 threads, peak memory per element,
#      beside a bare linear CST membrane kernel of our own (the floor);
#   2. the pure-.edp alternative: a linear membrane whose forces come from a
#      varf re-assembled every step;
#   3. the ballistic scene with every knob against a reference run (finest
#      mesh, small step factor, full physics): accuracy and cost.
# Writes results/bench/: speed.json, kernel.jsonl, tradeoff.csv, tradeoff.md,
# pareto.png, runs/*/ (each run's own results). Run from the repository root.
# BENCH_QUICK=1 runs a reduced set (small meshes, short runs) to check the
# pipeline in a minute; BENCH_TABLES=1 only remakes the tables and the plot
# from the runs already in results/bench.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root" || exit 1
out=results/bench
mkdir -p "$out/runs"
quick=${BENCH_QUICK:-0}
ff() { sh tools/ff.sh "$@"; }
now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.2f", b - a }'; }

tables_only=${BENCH_TABLES:-0}
if [ "$tables_only" != 1 ]; then
echo "== 1. kernel speed (build/bench/kernel_speed)"
: > "$out/kernel.jsonl"
if [ "$quick" = 1 ]; then sizes="0.67:200"; else sizes="0.67:400 0.21:60 0.067:8"; fi
for et in tri quad; do
    for sz in $sizes; do
        f=${sz%%:*}; steps=${sz##*:}
        for th in 1 2; do
            [ "$et" = quad ] && [ "$th" = 2 ] && continue
            line=$(OMP_WAIT_POLICY=passive build/bench/kernel_speed "$et" "$f" "$th" "$steps") || {
                echo "kernel_speed $et $f $th failed"; continue; }
            echo "$line" | tee -a "$out/kernel.jsonl"
        done
    done
done

echo "== 2. pure .edp varf step, and the King step on the same mesh"
edp=$(ff bench/edp_varf.edp -steps 20 | grep '^{') || edp='{}'
echo "$edp"
king_default=$(build/bench/kernel_speed tri 1 1 400) || king_default='{}'
echo "$king_default"
echo "== 2b. the paper's scene at its defaults, start to plots"
t0=$(now)
ff freefem_scripts/ballistic_impact.edp -out "$out/runs/scene_default" > "$out/runs/scene_default.log" 2>&1
scene_wall=$(elapsed "$t0")
echo "scene_default $scene_wall s"

echo "== 3. speed vs accuracy on the ballistic scene"
tend=2.5e-3
[ "$quick" = 1 ] && tend=0.5e-3
scene() { # name, then scene options
    name=$1; shift
    dir="$out/runs/$name"
    rm -rf "$dir"
    t0=$(now)
    if ff freefem_scripts/ballistic_impact.edp -out "$dir" -tend "$tend" -plots 0 -vtkdt 1 "$@" \
        > "$dir.log" 2>&1; then
        echo "$name $(elapsed "$t0") s"
    else
        echo "$name FAILED (see $dir.log)"; tail -3 "$dir.log"
    fi
    echo "$(elapsed "$t0")" > "$dir.wall"
}
if [ "$quick" = 1 ]; then
    scene reference -mesh default -dtfactor 0.5
else
    scene reference -mesh finest -dtfactor 0.6 -threads 2
fi
scene mesh_coarse -mesh coarse
scene mesh_default -mesh default
[ "$quick" = 1 ] || scene mesh_fine -mesh fine
[ "$quick" = 1 ] || scene mesh_finer -mesh finer -threads 2
scene quads_default -mesh default -elements quad
scene dtfactor_0.5 -dtfactor 0.5
scene dtfactor_0.95 -dtfactor 0.95
scene amplitude_mass_x10 -massfactor 10
scene amplitudes_static -amplitudes static
scene no_locking -set K_d=0
scene no_bending -set kb_1=0,kb_2=0
scene no_shear_flow -set gammadot_0=0
scene clamp_friction -clamp friction
scene linear_yarns -material freefem_scripts/materials/kevlar_linear.txt -preload 0
scene contact_all_nodes -contact all
[ "$quick" = 1 ] || scene threads_2 -threads 2

fi # tables_only

echo "== 4. tables and plots"
cc -std=gnu11 -O2 -o build/bench/compare bench/compare.c -lm || exit 1
echo "run,elements,steps,wall_seconds,element_steps,apex_l2_error,peak_error,peak_time_error_s,profile_l2_error" \
    > "$out/tradeoff.csv"
for dir in "$out"/runs/*/; do
    name=$(basename "$dir")
    [ -f "$dir/summary.json" ] && [ -f "$out/runs/$name.wall" ] || continue
    get() { sed -n "s/.*\"$1\": \([^,]*\),.*/\1/p" "$dir/summary.json" | head -1; }
    els=$(get elements); steps=$(get steps); wall=$(cat "$out/runs/$name.wall")
    errs=$(build/bench/compare "$out/runs/reference" "$dir" 2>/dev/null || echo "nan,nan,nan,nan")
    echo "$name,$els,$steps,$wall,$(awk -v a="$els" -v b="$steps" 'BEGIN{printf "%.0f", a*b}'),$errs" \
        >> "$out/tradeoff.csv"
done
awk -F, 'NR == 1 { print "| run | elements | steps | wall s | apex L2 error | peak error | peak time error (ms) | profile error at 2 ms |";
                   print "|---|---|---|---|---|---|---|---|"; next }
         { printf "| %s | %s | %s | %s | %.2g %% | %+.2g %% | %+.3f | %.2g %% |\n", $1, $2, $3, $4, 100*$6, 100*$7, 1e3*$8, 100*$9 }' \
    "$out/tradeoff.csv" > "$out/tradeoff.md"
cat "$out/tradeoff.md"
cat > "$out/pareto.gp" <<EOF
set datafile separator ','
set terminal pngcairo size 900,600
set output '$out/pareto.png'
set title 'Ballistic scene: accuracy against cost (error of the apex history vs the reference)'
set xlabel 'wall time (s)'; set ylabel 'relative L2 error of the apex history, 0-2.5 ms'
set termoption noenhanced
set logscale xy; set grid; set key top right
# numerical knobs (same physics) and physics changes (another answer) apart
num(n) = (n eq 'clamp_friction' || n eq 'linear_yarns' || n eq 'no_bending' || n eq 'no_locking' || n eq 'no_shear_flow') ? 0 : 1
plot '$out/tradeoff.csv' every ::1 using 4:((\$6 > 0 && num(strcol(1))) ? \$6 : 1/0) with points pt 7 ps 1.5 lc 1 title 'numerical knobs (mesh, step, amplitudes, elements, threads, contact search)', \
     '' every ::1 using 4:((\$6 > 0 && !num(strcol(1))) ? \$6 : 1/0) with points pt 5 ps 1.3 lc 7 title 'physics left out or changed', \
     '' every ::1 using 4:(\$6 > 0 ? \$6 : 1/0):1 with labels offset 1,0.6 left font ',7' notitle
EOF
gnuplot "$out/pareto.gp" || echo "gnuplot failed"
[ "$tables_only" = 1 ] && { echo "results in $out (tables and plot only)"; exit 0; }

# speed.json: the figures of 1 and 2 in one place, with the ratios the targets name
num() { echo "$1" | sed -n "s/.*\"$2\": \([^,}]*\).*/\1/p"; }
pick() { grep "\"element_type\": \"$1\"" "$out/kernel.jsonl" | grep "\"threads\": $2," | \
         awk -v n="$3" -F'"elements": ' '{ split($2, a, ","); if (a[1] + 0 >= n) { print; exit } }'; }
k50_1=$(pick tri3 1 40000); k50_2=$(pick tri3 2 40000)
king_ns=$(num "$king_default" ns_per_element_step); edp_ns=$(num "$edp" ns_per_element_step)
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (a > 0 && b > 0) printf "%.2f", a / b; else print "null" }'; }
{
    echo "{"
    echo "  \"kernel\": ["
    sed 's/^/    /; $!s/$/,/' "$out/kernel.jsonl"
    echo "  ],"
    echo "  \"edp_varf\": $edp,"
    echo "  \"king_default_mesh\": $king_default,"
    echo "  \"scene_default_wall_seconds\": $scene_wall,"
    echo "  \"ratios\": {"
    echo "    \"king_over_linear_membrane_50k_1thread\": $(ratio "$(num "$k50_1" ns_per_element_step)" "$(num "$k50_1" linear_membrane_ns)"),"
    echo "    \"edp_varf_over_king_default_mesh\": $(ratio "$edp_ns" "$king_ns"),"
    echo "    \"one_over_two_threads_50k\": $(ratio "$(num "$k50_1" ns_per_element_step)" "$(num "$k50_2" ns_per_element_step)")"
    echo "  }"
    echo "}"
} > "$out/speed.json.tmp" && mv "$out/speed.json.tmp" "$out/speed.json"
cat "$out/speed.json"
echo "results in $out"
