#!/bin/sh
# One run per folder, hostile paths, cost before it is spent.
#   lock: a second run into a folder in use refuses (exit 2, naming the pid);
#     a stale lock of a dead process is taken over with a note.
#   earlier results: a new run into them refuses (exit 2) unless -overwrite 1,
#     which clears them (old frames and pictures gone); a folder that is not a
#     wovenff run's is never cleared.
#   paths: -out with a single quote, a space, unicode works (pictures drawn,
#     nothing run by a shell: a "; touch" in the path creates nothing); a
#     newline is refused with a message.
#   cost: -dtfactor 1e-6 (steps above -maxsteps) and -vtkdt 1e-9 (output above
#     -maxoutput) stop before the loop with exit 2, the estimate and the option.
set -u
tmp="${WFF_TEST_TMP:-/tmp}/run_folder"
rm -rf "$tmp"; mkdir -p "$tmp"
scene=freefem_scripts/ballistic_impact.edp
short="-mesh coarse -tend 0.1e-3 -vtkdt 1e-4"
fail=0
run() { # name expected-exit args...
    name=$1; want=$2; shift 2
    sh tools/ff.sh "$scene" "$@" > "$tmp/$name.log" 2>&1
    rc=$?
    [ "$rc" -eq "$want" ] || { echo "$name: exit $rc, want $want"; tail -4 "$tmp/$name.log" | sed 's/^/    /'; fail=1; }
}
says() { grep -qF -- "$2" "$tmp/$1.log" || { echo "$1: output lacks '$2'"; tail -3 "$tmp/$1.log"; fail=1; }; }

# ---- two runs into one folder
sh tools/ff.sh "$scene" -mesh coarse -tend 1.5e-3 -plots 0 -vtkdt 1 -out "$tmp/busy" > "$tmp/first.log" 2>&1 &
first=$!
for i in $(seq 100); do [ -f "$tmp/busy/.wovenff.lock" ] && break; sleep 0.05; done
run second 2 $short -plots 0 -out "$tmp/busy"
says second "is in use by another run (process $first holds"
wait $first || { echo "first run: failed"; fail=1; }
grep -q '"status": "ok"' "$tmp/busy/summary.json" || { echo "first run: no ok summary"; fail=1; }
[ -f "$tmp/busy/.wovenff.lock" ] && { echo "the lock was not released at the end"; fail=1; }
[ "$(grep -c '' "$tmp/busy/history.csv")" -eq 152 ] || { echo "busy history: rows of two runs?"; fail=1; }
echo "two runs into one folder: the second refused"

# ---- a stale lock (a dead pid) is taken over
mkdir -p "$tmp/stale"
sh -c 'echo $$ > "$1"' sh "$tmp/stale/.wovenff.lock"
run stale 0 $short -plots 0 -out "$tmp/stale"
says stale "which no longer runs (a killed run); taking it over"

# ---- earlier results: refused, then -overwrite 1 clears them
run again 2 $short -plots 0 -out "$tmp/stale"
says again "holds an earlier run's files: choose another -out, or -overwrite 1"
touch "$tmp/stale/vtk/frame_99.vtu" "$tmp/stale/contour_3.png"
run overwrite 0 $short -plots 0 -out "$tmp/stale" -overwrite 1
[ -f "$tmp/stale/vtk/frame_99.vtu" ] || [ -f "$tmp/stale/contour_3.png" ] && { echo "overwrite: old files left"; fail=1; }
mkdir -p "$tmp/home"; echo keep > "$tmp/home/notes.txt"
run foreign 2 $short -plots 0 -out "$tmp/home" -overwrite 1
says foreign "holds files that are not a wovenff run's"
[ -f "$tmp/home/notes.txt" ] || { echo "foreign: a user's file was removed"; fail=1; }
echo "earlier results: refused, -overwrite clears a run's folder only"

# ---- paths: a quote, a space, unicode, a shell command; a newline
for p in "it's here" "two words" "ünïcødé" "x'; touch $tmp/pwned; '"; do
    out="$tmp/paths/$p"
    run path 0 -mesh coarse -tend 0.45e-3 -vtkdt 1e-4 -plots 1 -out "$out"
    [ -s "$out/energy.png" ] && [ -s "$out/contour_0.png" ] || { echo "path '$p': pictures missing"; fail=1; }
    grep -q '"status": "ok"' "$out/summary.json" || { echo "path '$p': no ok summary"; fail=1; }
done
[ -e "$tmp/pwned" ] && { echo "a path ran a shell command"; fail=1; }
nl="$tmp/new
line"
run newline 2 $short -plots 0 -out "$nl"
says newline "-out '$tmp/new\\nline': a value with a control character (a tab, a newline, ...) is refused"
[ -e "$nl" ] && { echo "newline: the folder was made"; fail=1; }
echo "paths: quote, space, unicode work, a newline is refused"

# ---- cost before it is spent
run steps 2 -mesh coarse -dtfactor 1e-6 -plots 0 -out "$tmp/steps"
says steps "more than -maxsteps 1e8 (raise -maxsteps"
says steps "estimate: "
run output 2 -mesh coarse -vtkdt 1e-9 -plots 0 -out "$tmp/output"
says output "more than -maxoutput 2 GB (raise -maxoutput"
[ -z "$(ls -A "$tmp/output" 2>/dev/null)" ] || { echo "output: the refused run left files"; fail=1; }
echo "cost: $(grep -m1 '^error:' "$tmp/steps.log" | cut -c1-120)"
exit $fail
