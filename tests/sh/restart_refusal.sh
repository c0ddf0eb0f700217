#!/bin/sh
# Restarts that cannot hurt: every refused restart exits 2 with a message
# naming what differs, and leaves the folder byte-identical (a hash of every
# file before and after) with no summary.json. Cases: a checkpoint copied
# from another run (other history), the checkpoint record edited (another row
# count), the history cut short, the material file edited since, another
# -threads, a restart into a folder holding another run. Then a valid restart
# still works (exit 0, "ok").
set -u
tmp="${WFF_TEST_TMP:-/tmp}/restart_refusal"
rm -rf "$tmp"; mkdir -p "$tmp"
scene=freefem_scripts/ballistic_impact.edp
cp freefem_scripts/materials/kevlar_s706.txt "$tmp/material.txt"
common="-mesh coarse -tend 0.3e-3 -plots 0 -vtkdt 1e-4 -material $tmp/material.txt"
fail=0
run() { # name expected-exit args...
    name=$1; want=$2; shift 2
    sh tools/ff.sh "$scene" "$@" > "$tmp/$name.log" 2>&1
    rc=$?
    [ "$rc" -eq "$want" ] || { echo "$name: exit $rc, want $want"; tail -5 "$tmp/$name.log" | sed 's/^/    /'; fail=1; }
}
hash_tree() { (cd "$1" && find . -type f | LC_ALL=C sort | xargs -d '\n' sha256sum); }
# refused NAME FOLDER PATTERN ARGS...: exit 2, PATTERN in the output, FOLDER unchanged
refused() {
    name=$1; dir=$2; pattern=$3; shift 3
    before=$(hash_tree "$dir")
    run "$name" 2 "$@"
    grep -qF -- "$pattern" "$tmp/$name.log" || { echo "$name: output lacks '$pattern'"; tail -3 "$tmp/$name.log"; fail=1; }
    [ "$(hash_tree "$dir")" = "$before" ] || { echo "$name: the refused restart changed $dir"; fail=1; }
    [ -f "$dir/summary.json" ] && { echo "$name: a summary.json was written"; fail=1; }
    echo "$name: refused, folder unchanged"
}

run A 9 $common -out "$tmp/A" -checkpoint 4 -stopafter 15
run X 9 $common -out "$tmp/X" -checkpoint 4 -stopafter 15 -velocity 25
[ "$(cat "$tmp/A/checkpoint/latest")" = 12 ] || { echo "A: no checkpoint at frame 12"; fail=1; }

# X's checkpoint copied into a copy of A, restarted with X's velocity: A's history is not X's
cp -R "$tmp/A" "$tmp/copied"; rm -rf "$tmp/copied/checkpoint"; cp -R "$tmp/X/checkpoint" "$tmp/copied/"
refused copied "$tmp/copied" "does not begin with the 14 lines the checkpoint at frame 12 recorded" \
    $common -restart "$tmp/copied" -velocity 25
# the checkpoint record edited to another row count
cp -R "$tmp/A" "$tmp/edited"
sed -i 's/^lines history.csv 14 /lines history.csv 10 /' "$tmp/edited/checkpoint/scene_12.txt"
refused edited "$tmp/edited" "is damaged or edited (its sum does not match its lines)" $common -restart "$tmp/edited"
# the history cut short
cp -R "$tmp/A" "$tmp/short"; head -n 10 "$tmp/A/history.csv" > "$tmp/short/history.csv"
refused short "$tmp/short" "does not begin with the 14 lines" $common -restart "$tmp/short"
# the material file edited since the checkpoint
cp -R "$tmp/A" "$tmp/material"; cp "$tmp/material.txt" "$tmp/material.orig"
printf '\n# edited\n' >> "$tmp/material.txt"
refused material "$tmp/material" "is not the one the checkpointed run read" $common -restart "$tmp/material"
cp "$tmp/material.orig" "$tmp/material.txt"
# another thread count (a run-defining option)
# (A ran with the default, the cores here: the checkpoint records the resolved count)
cp -R "$tmp/A" "$tmp/threads"
used=$(sed -n 's/^option -threads //p' "$tmp/A/checkpoint/scene_12.txt")
[ -n "$used" ] && [ "$used" -ge 1 ] || { echo "threads: the checkpoint records -threads '$used'"; fail=1; }
other=$(( used == 1 ? 2 : 1 ))
refused threads "$tmp/threads" "-threads is $other here but $used in the checkpointed run" $common -restart "$tmp/threads" -threads $other
# into a folder holding another run's results
refused occupied "$tmp/X" "holds an earlier run's files" $common -restart "$tmp/A" -out "$tmp/X"
# A itself untouched by all of that, and its restart still works
run valid 0 $common -restart "$tmp/A"
grep -q '"status": "ok"' "$tmp/A/summary.json" || { echo "valid: summary not ok"; fail=1; }
exit $fail
