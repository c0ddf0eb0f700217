#!/bin/sh
# Write faults and crashes leave no lie behind.
#   ulimit -f: a file-size limit (SIGXFSZ is ignored by the module, so the
#     write fails with "File too large") at several sizes: the run stops with
#     exit 3 and a message naming the file and strerror; no "status": "ok";
#     every CSV row whole; every JSON file parses; no .tmp left.
#   a full disk (a small tmpfs in a mount namespace): exit 3 naming the file
#     and "No space left on device", no .tmp left, every file whole.
#   kill -9 at several moments of a run (with checkpoints), each reached by
#     watching the folder: every file left is whole (CSV rows complete, JSON
#     parses, VTU/PVD end with </VTKFile>), no "ok" summary without its
#     pictures, and the restart from what is left completes with "ok", the
#     pictures and no .tmp (as does a rerun with -overwrite 1), also when
#     killed after the last checkpoint.
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

# ---- a full disk (a tmpfs of a few hundred kB in a mount namespace of our own: ENOSPC, not
# a size limit) at several sizes: exit 3 (or 0 if it all fitted), no .tmp left, every file whole,
# no "ok" summary on a failure
if unshare -rm true 2>/dev/null; then
    for kb in 96 320 600 680 720; do
        out="$tmp/disk_$kb"; mnt="$tmp/mnt_$kb"; mkdir -p "$mnt" "$out"
        unshare -rm sh -c 'mount -t tmpfs -o size="$1"k none "$2" || exit 99
            sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse -tend 0.45e-3 -vtkdt 1e-4 \
                -plots 1 -checkpoint 5 -out "$2/run" > "$3.log" 2>&1
            echo $? > "$3.rc"; cp -R "$2/run/." "$3/"' sh "$kb" "$mnt" "$out"
        rc=$(cat "$out.rc" 2>/dev/null || echo none)
        case $rc in
            0) grep -qs '"status": "ok"' "$out/summary.json" || { echo "disk ${kb}k: exit 0 without ok"; fail=1; } ;;
            3) grep -q "^error: .*No space left on device" "$out.log" \
                   || { echo "disk ${kb}k: no 'No space left' message"; tail -3 "$out.log"; fail=1; }
               grep -qs '"status": "ok"' "$out/summary.json" && { echo "disk ${kb}k: summary says ok"; fail=1; } ;;
            *) echo "disk ${kb}k: exit $rc, want 3 (or 0)"; tail -4 "$out.log"; fail=1 ;;
        esac
        [ -z "$(find "$out" -name '*.tmp*')" ] || { echo "disk ${kb}k: .tmp files left: $(find "$out" -name '*.tmp*')"; fail=1; }
        whole "$out" "disk ${kb}k"
        echo "disk ${kb}k: exit $rc, $(grep -m1 '^error:' "$out.log" | cut -c1-110)"
    done
else
    echo "full disk: not tested (no mount namespace here: unshare -rm refused)"
fi

# ---- kill -9 at moments of a run with checkpoints and pictures (each reached by watching the
# folder, not by a clock): mid-run after a checkpoint, while a picture is drawn in the
# background, after the last checkpoint (frame 45 of 45). Every file left is whole; the restart
# finishes (exit 0, "ok", the history equal to the uninterrupted run's, the pictures there, no
# .tmp left: the picture being drawn died with the scene and its .tmp is removed), and so does a
# rerun with -overwrite 1
ref="$tmp/ref"
sh tools/ff.sh "$scene" $common -tend 0.45e-3 -vtkdt 1e-4 -out "$ref" > "$ref.log" 2>&1 || { echo "ref run failed"; fail=1; }
# moment DIR: 0 once the moment has come
moment() {
    case $1 in
        mid) [ "$(cat "$2/checkpoint/latest" 2>/dev/null)" = 10 ] ;;
        picture) [ -n "$(find "$2" -maxdepth 1 -name '*.png.tmp' 2>/dev/null)" ] ;;
        last) [ "$(cat "$2/checkpoint/latest" 2>/dev/null)" = 45 ] ;;
    esac
}
args="$common -tend 0.45e-3 -vtkdt 1e-4 -checkpoint 5"
for when in mid picture last; do
    tries=0; state=""
    while [ $tries -lt 3 ] && [ "$state" != killed ]; do
        tries=$((tries + 1))
        out="$tmp/kill_$when"; rm -rf "$out"
        sh tools/ff.sh "$scene" $args -out "$out" > "$out.log" 2>&1 &
        pid=$!
        i=0
        while [ $i -lt 4000 ] && kill -0 "$pid" 2>/dev/null && ! moment $when "$out"; do sleep 0.005; i=$((i + 1)); done
        # kill FreeFem++ itself (tools/ff.sh execs it: the same pid)
        kill -9 "$pid" 2>/dev/null
        wait "$pid" 2>/dev/null
        state=killed
        grep -qs '"status": "ok"' "$out/summary.json" && state="finished first"
    done
    [ "$state" = killed ] || { echo "kill $when: the run finished before the moment, 3 times"; fail=1; continue; }
    whole "$out" "kill $when"
    left=$(find "$out" -name '*.tmp*' | wc -l)
    cp -R "$out" "$out.copy"
    sh tools/ff.sh "$scene" $args -restart "$out" > "$out.restart.log" 2>&1
    rc=$?
    [ "$rc" -eq 0 ] || { echo "kill $when: restart exit $rc"; tail -3 "$out.restart.log"; fail=1; }
    grep -q "taking it over" "$out.restart.log" || { echo "kill $when: stale lock not reported"; fail=1; }
    grep -qs '"status": "ok"' "$out/summary.json" || { echo "kill $when: restarted summary not ok"; fail=1; }
    cmp -s "$ref/history.csv" "$out/history.csv" || { echo "kill $when: restarted history differs"; fail=1; }
    for p in apex energy profiles contour_0; do
        [ -s "$out/$p.png" ] || { echo "kill $when: restarted run lacks $p.png"; fail=1; }
    done
    [ -z "$(find "$out" -name '*.tmp*')" ] || { echo "kill $when: .tmp left after the restart: $(find "$out" -name '*.tmp*')"; fail=1; }
    whole "$out" "kill $when, restarted"
    sh tools/ff.sh "$scene" $args -out "$out.copy" -overwrite 1 > "$out.overwrite.log" 2>&1 \
        || { echo "kill $when: rerun with -overwrite 1 failed"; fail=1; }
    [ -z "$(find "$out.copy" -name '*.tmp*')" ] || { echo "kill $when: .tmp left after -overwrite 1"; fail=1; }
    echo "kill $when: files whole, $left .tmp left by the kill; restarted from frame $(grep -o 'checkpoint at frame [0-9]*' "$out.restart.log" | cut -d' ' -f4), no .tmp after it, history equal, pictures there"
done
exit $fail
