#!/bin/sh
# make bench: what wovenff's knobs cost and what they buy. Not part of make test.
#   1. kernel speed: ns per element-step of the King step on tri3 and quad4 at
#      ~5k, ~50k and ~500k elements, 1 and 2 threads, peak memory per element,
#      beside a bare linear CST membrane kernel of our own (the floor);
#   2. the pure-.edp alternative: a linear membrane whose forces come from a
#      varf re-assembled every step;
#   2c. the scripted explicit loop against the built-in one at ~5k and ~50k
#      elements, and the µs per call of each loop operator (bench/loop.sh);
#   3. the ballistic scene with every knob against a reference run (finest
#      mesh, small step factor, full physics): accuracy and cost.
#   2e. a pack of 8 plies on the default mesh to 3 ms: wall, ns per element-step,
#      ply contact's share, threads' speed-up (bench/pack_bench.sh, pack.md);
#   2d. the rest of issue 12's speed table: the strip scene at its defaults,
#      -amplitudes static against dynamic per step.
# Writes results/bench/: speed.json, speed.md, kernel.jsonl, scenes.txt,
# tradeoff.csv, tradeoff.md, pareto.png, runs/*/ (each run's own results). Run
# from the repository root. speed.md and speed.json's rows (one key per row of
# issue 12's table; the keys and what each ratio is: bench/speed_table.sh) are
# made by bench/speed_table.sh from kernel.jsonl and scenes.txt.
# BENCH_QUICK=1 (make bench QUICK=1, ~3 min) runs the speed table's kernel and
# scene figures only (fewer steps, short amplitude runs; no parts 2, 2c, 3);
# BENCH_TABLES=1 only remakes the tables and the plot from the runs already in
# results/bench.
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
tend=2.5e-3   # end time of the runs of part 3 (the plot names it too)
[ "$quick" = 1 ] && tend=0.5e-3
if [ "$tables_only" != 1 ]; then
echo "== 1. kernel speed (build/bench/kernel_speed)"
: > "$out/kernel.jsonl"
# each run: element type, size factor (0.67: ~5k, 0.21: ~50k, 0.067: ~493k triangles),
# threads, steps; the line gets "size_factor" (bench/speed_table.sh picks rows by it)
if [ "$quick" = 1 ]; then
    runs="tri:0.21:1:30 tri:0.21:2:30 quad:0.21:1:10 tri:0.067:1:4"
else
    runs=""
    for et in tri quad; do
        for sz in 0.67:400 0.21:60 0.067:8; do
            for th in 1 2; do
                [ "$et" = quad ] && [ "$th" = 2 ] && continue
                runs="$runs $et:${sz%%:*}:$th:${sz##*:}"
            done
        done
    done
fi
for r in $runs; do
    et=${r%%:*}; r=${r#*:}; f=${r%%:*}; r=${r#*:}; th=${r%%:*}; steps=${r#*:}
    line=$(OMP_WAIT_POLICY=passive build/bench/kernel_speed "$et" "$f" "$th" "$steps") || {
        echo "kernel_speed $et $f $th failed"; continue; }
    echo "$line" | sed "s/^{/{\"size_factor\": $f, /" | tee -a "$out/kernel.jsonl"
done

edp='{}'; king_default='{}'
if [ "$quick" != 1 ]; then
echo "== 2. pure .edp varf step, and the King step on the same mesh"
edp=$(ff bench/edp_varf.edp -steps 20 | grep '^{') || edp='{}'
echo "$edp"
king_default=$(build/bench/kernel_speed tri 1 1 400) || king_default='{}'
echo "$king_default"
fi
# cpu = user + system CPU seconds of every child process that has ended so far
# (`times` run in this shell: in a $(...) subshell it would see no children)
children_cpu() { times > "$out/.times"; cpu=$(awk 'NR == 2 { split($1, u, /[ms]/); split($2, s, /[ms]/)
                 printf "%.3f", 60 * (u[1] + s[1]) + u[2] + s[2] }' "$out/.times"); rm -f "$out/.times"; }
echo "== 2b. the paper's scene at its defaults, start to plots"
rm -rf "$out/runs/scene_default"   # (a results folder holding a run refuses a new one)
t0=$(now); children_cpu; c0=$cpu
ff freefem_scripts/ballistic_impact.edp -out "$out/runs/scene_default" > "$out/runs/scene_default.log" 2>&1
scene_wall=$(elapsed "$t0"); children_cpu; scene_cpu=$(awk -v a="$c0" -v b="$cpu" 'BEGIN { printf "%.2f", b - a }')
scene_summary=$(sed -n 's/^done in [^:]*: \(peak displacement .* %\), largest penetration.*/\1/p' \
                "$out/runs/scene_default.log")
echo "scene_default $scene_wall s ($scene_cpu s CPU): $scene_summary"

echo "== 2d. the strip scene at its defaults, start to plots; -amplitudes static against dynamic"
rm -rf "$out/runs/strip_default"
t0=$(now); children_cpu; c0=$cpu
if ff freefem_scripts/strip_tension.edp -out "$out/runs/strip_default" > "$out/runs/strip_default.log" 2>&1
then strip_wall=$(elapsed "$t0"); children_cpu; strip_cpu=$(awk -v a="$c0" -v b="$cpu" 'BEGIN { printf "%.2f", b - a }')
     echo "strip_default $strip_wall s ($strip_cpu s CPU)"
else strip_wall=""; strip_cpu=""; echo "strip_default FAILED (see $out/runs/strip_default.log)"; fi
# per step: full mode takes part 3's mesh_default and amplitudes_static runs (to 2.5 ms);
# quick mode runs this pair to 0.5 ms
amp_dynamic=runs/mesh_default/summary.json; amp_static=runs/amplitudes_static/summary.json
if [ "$quick" = 1 ]; then
    for a in dynamic static; do
        rm -rf "$out/runs/amplitudes_${a}_quick"
        ff freefem_scripts/ballistic_impact.edp -out "$out/runs/amplitudes_${a}_quick" -tend 0.5e-3 -plots 0 \
            -vtkdt 1 -amplitudes "$a" > "$out/runs/amplitudes_${a}_quick.log" 2>&1 || echo "amplitudes $a FAILED"
    done
    amp_dynamic=runs/amplitudes_dynamic_quick/summary.json; amp_static=runs/amplitudes_static_quick/summary.json
fi

if [ "$quick" != 1 ]; then
echo "== 2e. a pack: 8 plies on the default mesh to 3 ms, 1 and 2 threads (bench/pack_bench.sh)"
sh bench/pack_bench.sh || echo "bench/pack_bench.sh failed"

echo "== 2c. the scripted explicit loop against the built-in one (bench/loop.sh)"
sh bench/loop.sh || echo "bench/loop.sh failed"

echo "== 3. speed vs accuracy on the ballistic scene"
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
scene reference -mesh finest -dtfactor 0.6 -threads 2
scene mesh_coarse -mesh coarse
scene mesh_default -mesh default
scene adapt_5 -mesh coarse -adapt 5     # adaptmesh every 5 frames from the coarse mesh
scene adapt_20 -mesh coarse -adapt 20
scene mesh_fine -mesh fine
scene mesh_finer -mesh finer -threads 2
scene quads_default -mesh default -elements quad
scene dtfactor_0.5 -dtfactor 0.5
scene dtfactor_0.95 -dtfactor 0.95
scene amplitude_mass_x10 -massfactor 10
scene amplitudes_static -amplitudes static
scene no_locking -set K_d=0
scene no_bending -set kb_1=0,kb_2=0
scene no_shear_flow -set gammadot_0=0
scene clamp_friction -clamp friction -clampforce 29e3   # 29 kN over the specimen: the row docs/speed.md measured (the default is 116 kN since issue 27)
scene linear_yarns -material freefem_scripts/materials/kevlar_linear.txt -preload 0
scene contact_all_nodes -contact all
scene zonal_2cm -zonal 0.02          # King within 2 cm of the impact point, fitted linear yarns beyond
scene zonal_4cm -zonal 0.04
scene zonal_8cm -zonal 0.08
scene threads_1 -threads 1   # the default is the cores this process may use
fi # quick

{   # the speed table's scene figures (bench/speed_table.sh reads them)
    echo "scene_wall_seconds $scene_wall"
    echo "scene_cpu_seconds $scene_cpu"
    echo "scene_summary $scene_summary"
    [ -n "$strip_wall" ] && echo "strip_wall_seconds $strip_wall" && echo "strip_cpu_seconds $strip_cpu"
    echo "amplitudes_dynamic_summary $amp_dynamic"
    echo "amplitudes_static_summary $amp_static"
} > "$out/scenes.txt"
fi # tables_only

if [ "$quick" != 1 ] || [ "$tables_only" = 1 ]; then

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
# pareto.png: error against wall time, each run a numbered point and a key
# beside the plot (number, run, wall time, error). The numbers are placed by a
# greedy search so none covers another or a point: beside the point if there is
# room, else further out with a thin leader line. The plot area is fixed in
# pixels so the search knows how large a number is in decades.
awk -F, -v ranges="$out/pareto_ranges.txt" -v key="$out/pareto_key.txt" \
    -v W=1150 -v H=650 -v left=0.08 -v right=0.72 -v bottom=0.11 -v top=0.91 '
function abs(v) { return v < 0 ? -v : v }
function free(x0, x1, y0, y1,    j) {   # is the box [x0, x1] x [y0, y1] (decades) free?
    if (x0 < xlo || x1 > xhi || y0 < ylo || y1 > yhi) return 0
    for (j = 1; j <= n; j++)   # the points, as boxes of a marker size
        if (X[j] + mx > x0 && X[j] - mx < x1 && Y[j] + my > y0 && Y[j] - my < y1) return 0
    for (j = 1; j <= placed; j++)
        if (x0 < B1[j] && x1 > B0[j] && y0 < C1[j] && y1 > C0[j]) return 0
    return 1
}
NR > 1 && $4 > 0 && $6 > 0 { n++; name[n] = $1; wall[n] = $4; err[n] = $6
                             X[n] = log($4) / log(10); Y[n] = log($6) / log(10) }
END {
    if (n == 0) { print "1 10 0.0001 1" > ranges; exit }   # no run to show: empty axes
    minX = minY = 1e9; maxX = maxY = -1e9
    for (i = 1; i <= n; i++) {
        if (X[i] < minX) minX = X[i]; if (X[i] > maxX) maxX = X[i]
        if (Y[i] < minY) minY = Y[i]; if (Y[i] > maxY) maxY = Y[i]
    }
    xlo = int(minX - 0.1 + 100) - 100; xhi = 100 - int(100 - (maxX + 0.1))      # whole decades
    ylo = int(minY - 0.2 + 100) - 100; yhi = 100 - int(100 - (maxY + 0.1))
    printf "%g %g %g %g\n", 10^xlo, 10^xhi, 10^ylo, 10^yhi > ranges
    px = (xhi - xlo) / (W * (right - left)); py = (yhi - ylo) / (H * (top - bottom))  # decades per pixel
    cw = 7 * px; hh = 7 * py; mx = 6 * px; my = 6 * py     # a digit, half a line, a marker
    for (i = 1; i <= n; i++) o[i] = i    # numbered from the top down
    for (i = 2; i <= n; i++) for (j = i; j > 1 && Y[o[j]] > Y[o[j - 1]]; j--) { t = o[j]; o[j] = o[j - 1]; o[j - 1] = t }
    for (k = 1; k <= n; k++) {
        i = o[k]; hw = cw * length(k "") / 2; done = 0
        for (ring = 1; ring <= 12 && !done; ring++)     # rings of 8 places around the point
            for (a = 0; a < 8 && !done; a++) {
                dx = ring * (mx + hw + 2 * px) * (a == 0 || a == 1 || a == 7 ? 1 : a >= 3 && a <= 5 ? -1 : 0)
                dy = ring * (my + hh + 1 * py) * (a >= 1 && a <= 3 ? 1 : a >= 5 ? -1 : 0)
                if (free(X[i] + dx - hw, X[i] + dx + hw, Y[i] + dy - hh, Y[i] + dy + hh)) {
                    done = 1; lx = X[i] + dx; ly = Y[i] + dy; far = ring > 1
                }
            }
        if (!done) { lx = X[i] + mx + hw; ly = Y[i]; far = 0 }
        placed++; B0[placed] = lx - hw; B1[placed] = lx + hw; C0[placed] = ly - hh; C1[placed] = ly + hh
        printf "%d,%s,%.6g,%.6g,%.6g,%.6g,%d\n", k, name[i], wall[i], err[i], 10^lx, 10^ly, far
        printf "%2d  %-20s %6.3g s  %7.2g %%\n", k, name[i], wall[i], 100 * err[i] > key
    }
}' "$out/tradeoff.csv" > "$out/pareto_labels.csv"
read xlo xhi ylo yhi < "$out/pareto_ranges.txt"
tend_ms=$(awk -v t="$tend" 'BEGIN { printf "%g", t * 1e3 }')
keytext=$(awk 'BEGIN { printf " #  run                   wall     error" } { printf "\\n%s", $0 }' "$out/pareto_key.txt")
cat > "$out/pareto.gp" <<EOF
set datafile separator ','
set terminal pngcairo size 1150,650 font ',10'
set output '$out/pareto.png'
set lmargin at screen 0.08; set rmargin at screen 0.72; set bmargin at screen 0.11; set tmargin at screen 0.91
set title 'Ballistic scene: accuracy against cost (error of the apex history against the reference run)'
set xlabel 'wall time (s)'; set ylabel 'relative L2 error of the apex history, 0-$tend_ms ms'
set logscale xy; set grid; set xrange [$xlo:$xhi]; set yrange [$ylo:$yhi]; set format y '10^{%L}'
set key at screen 0.74, screen 0.91 left top Left reverse samplen 1 noenhanced
set label 1 "$keytext" at screen 0.74, screen 0.80 left front font 'DejaVu Sans Mono,8' noenhanced
# numerical knobs (same physics) and physics changes (another answer) apart
num(n) = (n eq 'clamp_friction' || n eq 'linear_yarns' || n eq 'no_bending' || n eq 'no_locking' || n eq 'no_shear_flow' || n[1:6] eq 'zonal_') ? 0 : 1
plot '$out/pareto_labels.csv' using 3:4:(\$7 > 0 ? \$5 - \$3 : 1/0):(\$6 - \$4) with vectors nohead lc rgb 'gray60' notitle, \
     '' using 3:(num(strcol(2)) ? \$4 : 1/0) with points pt 7 ps 1.3 lc 1 title 'numerical knobs (same physics)', \
     '' using 3:(num(strcol(2)) ? 1/0 : \$4) with points pt 5 ps 1.1 lc 7 title 'physics left out or changed', \
     '' using 5:6:1 with labels center font ',8' notitle
EOF
gnuplot "$out/pareto.gp" || echo "gnuplot failed"
fi # quick (no part 3: no tradeoff table, no plot)
sh bench/speed_table.sh "$out" "$out" || echo "bench/speed_table.sh failed"
cat "$out/speed.md"
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
    # issue 12's speed table, one key per row (bench/speed_table.sh)
    sed '1d; $d; $!s/[^,]$/&,/' "$out/speed_table.json"
    # the scripted loop's rows (bench/loop.sh): scripted_loop_ns_5k, builtin_ns_5k, ...
    [ "$quick" != 1 ] && [ -s "$out/loop.json" ] && sed -n 's/^    \("[a-z_0-9]*": .*\),$/  \1,/p' "$out/loop.json"
    echo "  \"ratios\": {"
    echo "    \"king_over_linear_membrane_50k_1thread\": $(ratio "$(num "$k50_1" ns_per_element_step)" "$(num "$k50_1" linear_membrane_ns)"),"
    echo "    \"edp_varf_over_king_default_mesh\": $(ratio "$edp_ns" "$king_ns"),"
    echo "    \"one_over_two_threads_50k\": $(ratio "$(num "$k50_1" ns_per_element_step)" "$(num "$k50_2" ns_per_element_step)")"
    echo "  }"
    echo "}"
} > "$out/speed.json.tmp" && mv "$out/speed.json.tmp" "$out/speed.json"
cat "$out/speed.json"
echo "results in $out"
