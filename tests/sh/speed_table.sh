#!/bin/sh
# bench/speed_table.sh (make bench's speed table, issue 12) on canned inputs, no
# timing: every row key is written, valid JSON; each ratio is the one its row
# names (King / CST, 1 thread / 2 threads, 493k / 50k, quad4 / tri3, static /
# dynamic µs per step, value / limit); met and missed follow each target's
# direction (>= for the thread speed-up, <= for the others) on both sides of it;
# the scene is missed when its summary numbers differ even if it is fast; a row
# with no input is "not measured" (met null); speed.md has one line per row.
set -u
tmp="${WFF_TEST_TMP:-/tmp}/speed_table"
rm -rf "$tmp"
mkdir -p "$tmp/a" "$tmp/b" "$tmp/c"
fail=0
check() { # description, then a command that must succeed
    what=$1; shift
    if "$@"; then :; else echo "FAIL: $what"; fail=1; fi
}
field() { # file key member: the member of row key in speed_table.json
    sed -n "s/^  \"$2\": {.*\"$3\": \([^,}]*\).*/\1/p" "$1"
}
kernel_line() { # size_factor type threads elements ns cst bytes rss
    printf '{"size_factor": %s, "elements": %s, "element_type": "%s", "nodes": 1, "threads": %s, "steps": 10, ' \
        "$1" "$4" "$2" "$3"
    printf '"ns_per_element_step": %s, "linear_membrane_ns": %s, "model_bytes_per_element": %s, ' "$5" "$6" "$7"
    printf '"peak_rss_bytes_per_element": %s}\n' "$8"
}
expected="peak displacement 31.8259 mm at 1.83001 ms, largest energy error 6.26259e-05 %"

# a: every target met, each exactly at or just inside its limit, rows in a shuffled
# order with a ~5k row that must not be picked
{
    kernel_line 0.67 tri3 1 5000 999 1 999 999
    kernel_line 0.067 tri3 1 493330 60 30 255 553
    kernel_line 0.21 tri3 2 50490 27.5 6 256 700
    kernel_line 0.21 quad4 1 26804 100 null 653 1049
    kernel_line 0.21 tri3 1 50490 50 20 256 700
} > "$tmp/a/kernel.jsonl"
printf '{\n  "status": "ok",\n  "steps": 1000,\n  "wall_seconds": 2.0,\n  "x": 1\n}\n' > "$tmp/a/dyn.json"
printf '{\n  "status": "ok",\n  "steps": 500,\n  "wall_seconds": 3.0,\n  "x": 1\n}\n' > "$tmp/a/sta.json"
{
    echo "scene_wall_seconds 4"
    echo "scene_cpu_seconds 3.9"
    echo "scene_summary $expected"
    echo "strip_wall_seconds 19.5"
    echo "strip_cpu_seconds 19.25"
    echo "amplitudes_dynamic_summary dyn.json"
    echo "amplitudes_static_summary $tmp/a/sta.json"
} > "$tmp/a/scenes.txt"
sh bench/speed_table.sh "$tmp/a" "$tmp/a" || { echo "FAIL: speed_table.sh exit $?"; exit 1; }
j="$tmp/a/speed_table.json"
check "valid JSON" python3 -c 'import json, sys; json.load(open(sys.argv[1]))' "$j"
keys="king_tri3_50k_1thread threads_2_vs_1_50k tri3_493k_vs_50k quad4_vs_tri3_50k
      amplitudes_static_vs_dynamic scene_make_run strip_scene_default memory_per_element"
for k in $keys; do
    check "row $k present" grep -q "^  \"$k\": {" "$j"
    check "row $k met" [ "$(field "$j" "$k" met)" = true ]
done
check "$(grep -c '' "$j") lines: a brace, 8 rows, a brace" [ "$(grep -c '' "$j")" -eq 10 ]
check "King / CST = 2.5" [ "$(field "$j" king_tri3_50k_1thread ratio)" = 2.500 ]
check "King value 50 ns" [ "$(field "$j" king_tri3_50k_1thread value)" = 50 ]
check "King against 20 ns" [ "$(field "$j" king_tri3_50k_1thread against)" = 20 ]
check "speed-up 50 / 27.5" [ "$(field "$j" threads_2_vs_1_50k ratio)" = 1.818 ]
check "493k / 50k = 1.2" [ "$(field "$j" tri3_493k_vs_50k ratio)" = 1.200 ]
check "quad4 / tri3 = 2" [ "$(field "$j" quad4_vs_tri3_50k ratio)" = 2.000 ]
check "static 6000 µs per step" [ "$(field "$j" amplitudes_static_vs_dynamic value)" = 6000 ]
check "dynamic 2000 µs per step" [ "$(field "$j" amplitudes_static_vs_dynamic against)" = 2000 ]
check "static / dynamic = 3" [ "$(field "$j" amplitudes_static_vs_dynamic ratio)" = 3.000 ]
check "scene 4 s = 1.0 of its limit" [ "$(field "$j" scene_make_run ratio)" = 1.000 ]
check "scene summary same" [ "$(field "$j" scene_make_run summary_same)" = true ]
check "strip 19.5 / 20" [ "$(field "$j" strip_scene_default ratio)" = 0.975 ]
check "strip CPU 19.25 s" [ "$(field "$j" strip_scene_default cpu_seconds)" = 19.25 ]
check "memory 256 B" [ "$(field "$j" memory_per_element value)" = 256 ]
check "peak RSS 700 B" [ "$(field "$j" memory_per_element peak_rss_bytes_per_element)" = 700 ]
m="$tmp/a/speed.md"
check "speed.md: header, rule, 8 rows" [ "$(grep -c '^|' "$m")" -eq 10 ]
check "speed.md: 8 met" [ "$(grep -v '^| figure |' "$m" | grep -c '| met |$')" -eq 8 ]

# b: every target just missed; the scene fast but its summary changed
{
    kernel_line 0.21 tri3 1 50490 50.1 20 256 700
    kernel_line 0.21 tri3 2 50490 27.9 6 256 700
    kernel_line 0.067 tri3 1 493330 61 30 255 553
    kernel_line 0.21 quad4 1 26804 101 null 653 1049
} > "$tmp/b/kernel.jsonl"
sed 's/"wall_seconds": 3.0/"wall_seconds": 3.1/' "$tmp/a/sta.json" > "$tmp/b/sta.json"
cp "$tmp/a/dyn.json" "$tmp/b/dyn.json"
{
    echo "scene_wall_seconds 2.0"
    echo "scene_summary peak displacement 31.8260 mm at 1.83001 ms, largest energy error 6.26259e-05 %"
    echo "strip_wall_seconds 20.1"
    echo "amplitudes_dynamic_summary dyn.json"
    echo "amplitudes_static_summary sta.json"
} > "$tmp/b/scenes.txt"
sh bench/speed_table.sh "$tmp/b" "$tmp/b" || { echo "FAIL: speed_table.sh exit $?"; exit 1; }
j="$tmp/b/speed_table.json"
check "valid JSON (b)" python3 -c 'import json, sys; json.load(open(sys.argv[1]))' "$j"
for k in king_tri3_50k_1thread threads_2_vs_1_50k tri3_493k_vs_50k quad4_vs_tri3_50k \
         amplitudes_static_vs_dynamic scene_make_run strip_scene_default; do
    check "row $k missed" [ "$(field "$j" "$k" met)" = false ]
done
check "memory still met" [ "$(field "$j" memory_per_element met)" = true ]
check "scene summary differs" [ "$(field "$j" scene_make_run summary_same)" = false ]
check "scene no CPU figure: null" [ "$(field "$j" scene_make_run cpu_seconds)" = null ]
check "speed.md: the changed summary named" grep -q 'summary differs.*31.8260 mm' "$tmp/b/speed.md"
check "speed.md: 7 missed" [ "$(grep -c '| \*\*missed\*\* |$' "$tmp/b/speed.md")" -eq 7 ]

# c: nothing measured but the 50k one-thread kernel line (no 2 threads, no 493k, no
# quads, no scenes.txt): those rows are there, not measured, never met
kernel_line 0.21 tri3 1 50490 50 20 256 700 > "$tmp/c/kernel.jsonl"
sh bench/speed_table.sh "$tmp/c" "$tmp/c" || { echo "FAIL: speed_table.sh exit $?"; exit 1; }
j="$tmp/c/speed_table.json"
check "valid JSON (c)" python3 -c 'import json, sys; json.load(open(sys.argv[1]))' "$j"
for k in threads_2_vs_1_50k tri3_493k_vs_50k quad4_vs_tri3_50k amplitudes_static_vs_dynamic \
         scene_make_run strip_scene_default; do
    check "row $k not measured" [ "$(field "$j" "$k" met)" = null ]
    check "row $k ratio null" [ "$(field "$j" "$k" ratio)" = null ]
done
check "King row still made" [ "$(field "$j" king_tri3_50k_1thread met)" = true ]
check "speed.md: 6 not measured" [ "$(grep -c '| not measured |$' "$tmp/c/speed.md")" -eq 6 ]

[ "$fail" -eq 0 ] && echo "speed table: keys, ratios, met / missed / not measured as expected"
exit "$fail"
