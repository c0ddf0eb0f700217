#!/bin/sh
# Checkpoint and restart of the ballistic scene (coarse mesh, to 0.45 ms):
#   ref   the run uninterrupted;
#   A     the same with -checkpoint 4, stopped abruptly after frame 15 (0.15 ms,
#         -stopafter: exit 9, no summary) -> checkpoint at frame 12; restarted
#         in place, stopped again after frame 43 (past the 0.4 ms profile) ->
#         checkpoint at frame 40;
#   B     restarted from A into another folder (-restart A -out B), to the end;
#   C     as B with another default thread count (OMP_NUM_THREADS=1, no -threads).
# B's history.csv and profiles.csv must equal ref's row for row (bitwise here:
# the explicit scheme is deterministic and the checkpoint holds all of its
# state; numbers are also compared to 1e-12 relative), and A keeps its files. A pack
# with erosion is restarted likewise (the last case).
# Then what a restart refuses: another -velocity (exit 2), a folder without a
# checkpoint (exit 2), a damaged checkpoint of every kind (a record or the model
# cut in half, a byte flipped, a NUL, longer, `latest` cut, garbled or naming
# another record: exit 2 naming the file before any file is touched: the folder
# stays byte-identical, no summary; tests/sh/restart_refusal.sh has more). And a
# run stopped after its last checkpoint (frame 45 of 45, at -tend exactly) is
# finished by its restart.
set -u
tmp="${WFF_TEST_TMP:-/tmp}/restart"
rm -rf "$tmp"
mkdir -p "$tmp"
scene=freefem_scripts/ballistic_impact.edp
common="-mesh coarse -tend 0.45e-3 -plots 0 -vtkdt 1e-4"
fail=0

run() { # name expected-exit args...
    name=$1; want=$2; shift 2
    sh tools/ff.sh "$scene" "$@" > "$tmp/$name.log" 2>&1
    rc=$?
    if [ "$rc" -ne "$want" ]; then
        echo "$name: exit $rc, want $want"; tail -5 "$tmp/$name.log" | sed 's/^/    /'; fail=1
    fi
}

run ref 0 $common -out "$tmp/ref"
run A_first 9 $common -out "$tmp/A" -checkpoint 4 -stopafter 15
[ -f "$tmp/A/summary.json" ] && { echo "a stopped run must leave no summary.json"; fail=1; }
[ "$(cat "$tmp/A/checkpoint/latest" 2>/dev/null)" = 12 ] || { echo "latest checkpoint is not frame 12"; fail=1; }
[ "$(wc -l < "$tmp/A/history.csv")" -eq 17 ] || { echo "A history: $(wc -l < "$tmp/A/history.csv") lines, want 17 (frames 0..15)"; fail=1; }
run A_second 9 $common -restart "$tmp/A" -checkpoint 4 -stopafter 43
grep -q "restarting from the checkpoint at frame 12" "$tmp/A_second.log" || { echo "A_second did not restart at frame 12"; fail=1; }
[ "$(cat "$tmp/A/checkpoint/latest" 2>/dev/null)" = 40 ] || { echo "latest checkpoint is not frame 40"; fail=1; }
ls "$tmp/A/checkpoint" | grep -q '_12\.' && { echo "the frame-12 checkpoint was not removed"; fail=1; }
cp "$tmp/A/history.csv" "$tmp/A_history_before.csv"
run B 0 $common -restart "$tmp/A" -out "$tmp/B"
grep -q '"restarted_from_frame": 40' "$tmp/B/summary.json" || { echo "B summary lacks restarted_from_frame 40"; fail=1; }
grep -q '"status": "ok"' "$tmp/B/summary.json" || { echo "B summary not ok"; fail=1; }
cmp -s "$tmp/A/history.csv" "$tmp/A_history_before.csv" || { echo "restarting into B changed A"; fail=1; }

# C: the same restart where the default thread count differs (OMP_NUM_THREADS=1,
# no -threads given): it continues with the checkpointed run's count, not refused
OMP_NUM_THREADS=1 run C 0 $common -restart "$tmp/A" -out "$tmp/C"
cmp -s "$tmp/B/history.csv" "$tmp/C/history.csv" || { echo "C (another default thread count) differs from B"; fail=1; }
[ "$(grep -o '"threads": [0-9]*' "$tmp/C/summary.json")" = "$(grep -o '"threads": [0-9]*' "$tmp/B/summary.json")" ] ||
    { echo "C did not continue with the checkpointed run's thread count"; fail=1; }

for f in history.csv profiles.csv ballistic.pvd; do
    if cmp -s "$tmp/ref/$f" "$tmp/B/$f"; then
        echo "$f: restarted run equals the uninterrupted one byte for byte"
    else
        echo "$f differs from the uninterrupted run:"; diff "$tmp/ref/$f" "$tmp/B/$f" | head -5; fail=1
    fi
done
# the same numerically (rows, and every number to 1e-12 relative)
awk -F, 'NR == FNR { row[FNR] = $0; n = FNR; next }
    { m = FNR; split(row[FNR], a, ","); if (NF != length(a)) { print "row " FNR ": column count"; bad = 1; next }
      for (i = 1; i <= NF; i++) if ($i != a[i]) { d = $i - a[i]; s = (a[i] < 0 ? -a[i] : a[i]);
          if (d < 0) d = -d; if (d > 1e-12 * s + 1e-300) { print "row " FNR " col " i ": " a[i] " vs " $i; bad = 1 } } }
    END { if (n != m) { print "rows: " n " vs " m; bad = 1 } exit bad }' \
    "$tmp/ref/history.csv" "$tmp/B/history.csv" || fail=1
for key in peak_displacement peak_time max_energy_error max_penetration steps final_projectile_velocity; do
    a=$(grep "\"$key\"" "$tmp/ref/summary.json"); b=$(grep "\"$key\"" "$tmp/B/summary.json")
    [ "$a" = "$b" ] || { echo "summary $key: '$a' vs '$b'"; fail=1; }
done

# refusals
run other_velocity 2 $common -restart "$tmp/A" -out "$tmp/C" -velocity 30
grep -qF -- "-velocity is 30 here but 22 in the checkpointed run" "$tmp/other_velocity.log" \
    || { echo "other_velocity: message missing"; cat "$tmp/other_velocity.log"; fail=1; }
run no_checkpoint 2 $common -restart "$tmp/ref" -out "$tmp/D"
grep -qF "no checkpoint there" "$tmp/no_checkpoint.log" || { echo "no_checkpoint: message missing"; fail=1; }
cp -R "$tmp/A" "$tmp/E"
ck="$tmp/E/checkpoint/model_40.bin"
size=$(wc -c < "$ck")
printf '\377' | dd of="$ck" bs=1 seek=$((size / 2)) conv=notrunc 2>/dev/null
hash_tree() { (cd "$1" && find . -type f | LC_ALL=C sort | xargs -d '\n' sha256sum); }
before=$(hash_tree "$tmp/E")
run damaged 2 $common -restart "$tmp/E"
grep -qF "is corrupt (checksum mismatch)" "$tmp/damaged.log" || { echo "damaged: message missing"; fail=1; }
[ "$(hash_tree "$tmp/E")" = "$before" ] || { echo "damaged: the refused restart changed the folder"; fail=1; }
[ -f "$tmp/E/summary.json" ] && { echo "damaged: a summary.json was written"; fail=1; }

# every other kind of damage to the checkpoint's files: exit 2 with an "error:" line naming the
# damaged file, the folder byte-identical, no summary (once: a record cut in half gave "Strange
# catch exception ???", exit 1; a NUL byte exit 8; a damaged `latest` named another file)
c=checkpoint
for kind in record_half record_flip record_longer record_nul model_half model_longer latest_half latest_text latest_empty latest_other; do
    rm -rf "$tmp/F"; cp -R "$tmp/A" "$tmp/F"; d="$tmp/F/$c"
    named="$d/scene_40.txt"
    case $kind in
        record_half) head -c $(($(wc -c < "$tmp/A/$c/scene_40.txt") / 2)) "$tmp/A/$c/scene_40.txt" > "$d/scene_40.txt" ;;
        record_flip) printf 'Q' | dd of="$d/scene_40.txt" bs=1 seek=40 conv=notrunc 2>/dev/null ;;
        record_longer) printf 'option -extra 1\n' >> "$d/scene_40.txt" ;;
        record_nul) printf '\000' | dd of="$d/scene_40.txt" bs=1 seek=60 conv=notrunc 2>/dev/null ;;
        model_half) named="$d/model_40.bin"
            head -c $(($(wc -c < "$tmp/A/$c/model_40.bin") / 2)) "$tmp/A/$c/model_40.bin" > "$d/model_40.bin" ;;
        model_longer) named="$d/model_40.bin"; printf 'xx' >> "$d/model_40.bin" ;;
        latest_half) named="$d/latest"; printf '4' > "$d/latest" ;;
        latest_text) named="$d/latest"; printf 'forty\n' > "$d/latest" ;;
        latest_empty) named="$d/latest"; : > "$d/latest" ;;
        latest_other) named="$d/scene_36.txt"   # a record renamed: not the frame `latest` names
            mv "$d/scene_40.txt" "$d/scene_36.txt"; mv "$d/model_40.bin" "$d/model_36.bin"; printf '36\n' > "$d/latest" ;;
    esac
    before=$(hash_tree "$tmp/F")
    run "damaged_$kind" 2 $common -restart "$tmp/F"
    grep "^error:" "$tmp/damaged_$kind.log" | grep -qF "$named" \
        || { echo "damaged $kind: no error line naming $named"; grep -v '^ *call' "$tmp/damaged_$kind.log" | tail -3; fail=1; }
    [ "$(hash_tree "$tmp/F")" = "$before" ] || { echo "damaged $kind: the refused restart changed the folder"; fail=1; }
    [ -f "$tmp/F/summary.json" ] && { echo "damaged $kind: a summary.json was written"; fail=1; }
done
echo "damaged checkpoints: 10 more kinds refused with exit 2, each naming its file, the folder unchanged"

# killed after its last checkpoint (frame 45 of 45: -stopafter 45 stops as a crash would, no
# summary): the checkpoint lies at -tend exactly (the model's t_stop), not past it, and the
# restart writes the outputs (summary "ok", the history equal to the uninterrupted run's)
# instead of being refused ("the checkpoint is already at 0.00045018 s")
run L_first 9 $common -out "$tmp/L" -checkpoint 5 -stopafter 45
[ "$(cat "$tmp/L/checkpoint/latest" 2>/dev/null)" = 45 ] || { echo "L: the last checkpoint is not frame 45"; fail=1; }
at=$(sed -n 's/^loop time //p' "$tmp/L/checkpoint/scene_45.txt")
awk -v t="$at" 'BEGIN { exit !(t == 0.45e-3) }' || { echo "L: the last checkpoint is at t = $at s, not -tend 0.00045 s"; fail=1; }
run L_restart 0 $common -restart "$tmp/L" -checkpoint 5
grep -q "restarting from the checkpoint at frame 45" "$tmp/L_restart.log" || { echo "L: not restarted from frame 45"; fail=1; }
grep -q '"status": "ok"' "$tmp/L/summary.json" || { echo "L: summary not ok"; fail=1; }
cmp -s "$tmp/ref/history.csv" "$tmp/L/history.csv" || { echo "L: the history differs from the uninterrupted run's"; fail=1; }
for key in peak_displacement peak_time steps final_projectile_velocity; do
    a=$(grep "\"$key\"" "$tmp/ref/summary.json"); b=$(grep "\"$key\"" "$tmp/L/summary.json")
    [ "$a" = "$b" ] || { echo "L: summary $key: '$a' vs '$b'"; fail=1; }
done
echo "killed after the last checkpoint (t = $at s = -tend): the restart finished, history equal"
# a pack (2 plies, failure on, 150 m/s: elements erode from 0.11 ms, perforated at 0.3 ms):
# checkpointed every 5 frames, stopped after frame 22 (the checkpoint at 0.2 ms holds eroded
# elements and each ply's accounts), restarted to the end: the uninterrupted run's files and
# state byte for byte (the pack's and the ply contact's state in the checkpoint, part.h)
pack="-mesh coarse -tend 0.4e-3 -plots 0 -vtkdt 1 -plies 2 -failure on -velocity 150 -threads 1"
run pack_ref 0 $pack -out "$tmp/pack_ref"
run pack_first 9 $pack -out "$tmp/P" -checkpoint 5 -stopafter 22
at=$(sed -n 's/^loop time //p' "$tmp/P/checkpoint/scene_20.txt" 2>/dev/null)
eroded_at=$(awk -F, -v t="$at" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "eroded_energy") c = i; next }
    $1 + 0 <= t + 0 && $c > 0 { n++ } END { print n + 0 }' "$tmp/P/history.csv")
[ "$eroded_at" -gt 0 ] || { echo "pack: no element eroded before the checkpoint at '$at' s: the case tests no erosion"; fail=1; }
run pack_restart 0 $pack -restart "$tmp/P" -out "$tmp/PB"
for f in history.csv profiles.csv; do
    cmp -s "$tmp/pack_ref/$f" "$tmp/PB/$f" || { echo "pack: $f differs from the uninterrupted run's"; fail=1; }
done
hash() { sed -n 's/.*"state_hash": "\([0-9a-f]*\)".*/\1/p' "$1/summary.json"; }
[ -n "$(hash "$tmp/PB")" ] && [ "$(hash "$tmp/PB")" = "$(hash "$tmp/pack_ref")" ] \
    || { echo "pack: state $(hash "$tmp/PB") after the restart, $(hash "$tmp/pack_ref") uninterrupted"; fail=1; }
grep -q '"perforated": true' "$tmp/PB/summary.json" || { echo "pack: the restarted run did not perforate"; fail=1; }
echo "a 2-ply pack with erosion (eroded before the checkpoint at $at s): restarted, the same state $(hash "$tmp/PB")"
exit $fail
