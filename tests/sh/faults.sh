#!/bin/sh
# Write faults and crashes leave no lie behind.
#   ulimit -f: a file-size limit (SIGXFSZ is ignored by the module, so the
#     write fails with "File too large") at several sizes: the run stops with
#     exit 3 and a message naming the file and strerror; no "status": "ok";
#     every CSV row whole; every JSON file parses; no .tmp left.
#   kill -9 at several moments of a run (with checkpoints): every file left is
#     whole (CSV rows complete, JSON parses, VTU/PVD end with </VTKFile>), no
#     "ok" summary without its pictures, and the restart from what is left
#     completes with "ok".
set -u
tmp="${WFF_TEST_TMP:-/tmp}/faults"
rm -rf "$tmp"; mkdir -p "$tmp"
scene=freefem_scripts/ballistic_impact.edp
common="-mesh coarse"
fail=0
# whole DIR: every file in DIR is whole
whole() {
    dir=$1; label=$2
    for f in $(find "$dir" -name '*.csv'); do
        # every line ends with a newline and has the header's column count
        [ -s "$f" ] || continue
        [ "$(tail -c 1 "$f" | od -An -c | tr -d ' ')" = '\n' ] || { echo "$label: $f ends mid-row"; fail=1; }
        awk -F, 'NR == 1 { n = NF } NF != n { bad = 1 } END { exit bad }' "$f" \
            || { echo "$label: $f has a row of another column count"; fail=1; }
    done
    for f in $(find "$dir" -name '*.json'); do
        python3 -c 'import json, sys; json.load(open(sys.argv[1]))' "$f" 2>/dev/null \
            || { echo "$label: $f is not valid JSON"; fail=1; }
    done
    for f in $(find "$dir" -name '*.vtu' -o -name '*.pvd'); do
        tail -c 20 "$f" | grep -q '</VTKFile>' || { echo "$label: $f is incomplete"; fail=1; }
    done
    if grep -qs '"status": "ok"' "$dir/summary.json"; then
        for p in apex energy profiles; do
            [ -s "$dir/$p.png" ] || [ ! -s "$dir/contour_0.png" ] || { echo "$label: ok without $p.png"; fail=1; }
        done
    fi
}

# ---- a file-size limit (blocks of 512 bytes: dash's ulimit -f) hitting: a history row (no VTK frames), a VTK frame
# (savevtk's ofstream: caught by the commit's completeness check), a picture
# (116 blocks, 59 392 bytes: above the coarse frame_0.vtu's 54.7 kB, below energy.png's 64.1 kB; 128
# blocks no longer reached the picture once the stable step took the vertices' amplitudes)
for case in "200 -tend 0.45e-3 -vtkdt 1 -frame 1e-6 -plots 0" "40 -tend 0.45e-3 -vtkdt 1e-4 -plots 0" "120 -tend 0.45e-3 -vtkdt 1 -plots 1" "116 -vtkdt 1 -tend 0.3e-3 -plots 1"; do
    set -- $case; limit=$1; shift
    out="$tmp/limit_$limit"
    ( ulimit -f "$limit"; exec sh tools/ff.sh "$scene" $common "$@" -out "$out" ) > "$out.log" 2>&1
    rc=$?
    [ "$rc" -eq 3 ] || { echo "limit $limit blocks: exit $rc, want 3"; tail -4 "$out.log"; fail=1; }
    grep -q "^error: .*File too large" "$out.log" || { echo "limit $limit blocks: no 'File too large' message"; tail -3 "$out.log"; fail=1; }
    grep -qs '"status": "ok"' "$out/summary.json" && { echo "limit $limit blocks: summary says ok"; fail=1; }
    grep -qs '"status": "failed"' "$out/summary.json" || { echo "limit $limit blocks: no failed summary"; fail=1; }
    [ -z "$(find "$out" -name '*.tmp*')" ] || { echo "limit $limit blocks: .tmp files left"; fail=1; }
    whole "$out" "limit $limit blocks"
    echo "limit $limit blocks: exit $rc, $(grep -m1 '^error:' "$out.log" | sed 's/.*: cannot/cannot/' | cut -c1-150)"
done

# ---- a file-size limit hitting the first checkpoint: exit 3 naming it, no "ok", and a later
# -restart of that folder is refused with a message (exit 2), not a read error
out="$tmp/limit_checkpoint"
( ulimit -f 120; exec sh tools/ff.sh "$scene" $common -tend 0.2e-3 -vtkdt 1 -plots 0 -checkpoint 2 -out "$out" ) \
    > "$out.log" 2>&1
rc=$?
[ "$rc" -eq 3 ] && grep -q "^error: wovenffSaveCheckpoint: cannot write checkpoint .*File too large" "$out.log" \
    || { echo "checkpoint under a file-size limit: exit $rc"; tail -3 "$out.log"; fail=1; }
grep -qs '"status": "ok"' "$out/summary.json" && { echo "checkpoint under a limit: summary says ok"; fail=1; }
whole "$out" "checkpoint under a limit"
sh tools/ff.sh "$scene" $common -tend 0.2e-3 -vtkdt 1 -plots 0 -checkpoint 2 -restart "$out" > "$out.restart.log" 2>&1
rc=$?
[ "$rc" -eq 2 ] && grep -q "^error: .*-restart .*no checkpoint there" "$out.restart.log" \
    || { echo "restart after a failed checkpoint: exit $rc"; tail -3 "$out.restart.log"; fail=1; }
echo "checkpoint under a limit: exit 3 ($(grep -m1 '^error:' "$out.log" | cut -c1-120)); its restart refused with exit 2"

# ---- kill -9 at several moments (the run with checkpoints every 4 frames)
ref="$tmp/ref"
sh tools/ff.sh "$scene" $common -tend 0.45e-3 -vtkdt 1e-4 -out "$ref" > "$ref.log" 2>&1 || { echo "ref run failed"; fail=1; }
for delay in 0.5 1.0 1.5 2.0 2.5; do
    out="$tmp/kill_$delay"
    sh tools/ff.sh "$scene" $common -tend 0.45e-3 -vtkdt 1e-4 -checkpoint 4 -out "$out" > "$out.log" 2>&1 &
    pid=$!
    sleep "$delay"
    # kill FreeFem++ itself (tools/ff.sh execs it: the same pid)
    kill -9 "$pid" 2>/dev/null
    wait "$pid" 2>/dev/null
    [ -d "$out" ] || { echo "kill at ${delay}s: before the folder"; continue; }
    whole "$out" "kill at ${delay}s"
    state="finished"
    grep -qs '"status": "ok"' "$out/summary.json" || state="killed"
    if [ "$state" = killed ] && [ -f "$out/checkpoint/latest" ]; then
        sh tools/ff.sh "$scene" $common -tend 0.45e-3 -vtkdt 1e-4 -checkpoint 4 -restart "$out" > "$out.restart.log" 2>&1 \
            || { echo "kill at ${delay}s: restart failed"; tail -3 "$out.restart.log"; fail=1; }
        grep -q "taking it over" "$out.restart.log" || { echo "kill at ${delay}s: stale lock not reported"; fail=1; }
        cmp -s "$ref/history.csv" "$out/history.csv" || { echo "kill at ${delay}s: restarted history differs"; fail=1; }
        state="$state, restarted from frame $(cat "$out/checkpoint/latest" 2>/dev/null)"
    fi
    echo "kill at ${delay}s: files whole ($state)"
done
exit $fail
