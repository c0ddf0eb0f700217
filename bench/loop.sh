#!/bin/sh
# The scripted explicit loop (freefem_scripts/explicit_loop.edp) against the
# built-in integrator on the same mesh and loading, at ~5k and ~50k elements:
# ns per element-step of each (CPU time, the scene's clock()), their ratio, and
# the µs per call of every loop operator (bench/loop_calls.edp). Writes
# results/bench/loop.json (bench/run.sh copies its rows into speed.json) and the
# runs' folders under results/bench/runs/loop_*. Run from the repository root:
#   sh bench/loop.sh          (about a minute; part of make bench)
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root" || exit 1
out=results/bench
mkdir -p "$out/runs"
get() { sed -n "s/.*\"$2\": \([^,]*\),.*/\1/p" "$1" | head -1; }
rows=""
# label, quarter-square divisions (2 n^2 triangles), end time (s)
for spec in 5k:50:1e-4 50k:158:2.5e-5; do
    label=${spec%%:*}; rest=${spec#*:}; n=${rest%%:*}; tend=${rest#*:}
    dir="$out/runs/loop_$label"
    rm -rf "$dir"
    if ! sh tools/ff.sh freefem_scripts/explicit_loop.edp -out "$dir" -n "$n" -tend "$tend" \
        -frame "$tend" -plots 0 > "$dir.log" 2>&1; then
        echo "explicit_loop -n $n FAILED (see $dir.log)"; tail -3 "$dir.log"; continue
    fi
    s=$(get "$dir/summary.json" scripted_ns_per_element_step)
    b=$(get "$dir/summary.json" builtin_ns_per_element_step)
    r=$(get "$dir/summary.json" scripted_to_builtin)
    e=$(get "$dir/summary.json" elements)
    d=$(get "$dir/summary.json" max_apex_difference)
    echo "loop $label: $e elements, scripted $s ns, built-in $b ns per element-step, ratio $r, apex difference $d"
    calls=$(sh tools/ff.sh bench/loop_calls.edp -n "$n" -reps $((n > 100 ? 20 : 200)) | grep '^{') || calls='{}'
    echo "calls $label: $calls"
    rows="$rows    \"scripted_loop_elements_$label\": $e,
    \"scripted_loop_ns_$label\": $s,
    \"builtin_ns_$label\": $b,
    \"scripted_loop_ratio_$label\": $r,
    \"scripted_loop_apex_difference_$label\": $d,
    \"loop_calls_$label\": $calls,
"
done
printf '{\n%s    "command": "sh bench/loop.sh"\n}\n' "$rows" > "$out/loop.json.tmp" && mv "$out/loop.json.tmp" "$out/loop.json"
cat "$out/loop.json"
