#!/bin/sh
# One model over MPI ranks gives the serial one-thread run's answer bit for bit
# (issue 28; docs/distributed.md), at 1, 2, 3 and 4 ranks (3 and 4 oversubscribed
# on a 2-core machine), through tools/ff.sh -np N (mpirun of FreeFem++-mpi with the
# MPI module build/mpi/wovenff.so; one rank: the MPI module under mpirun -np 1 for the
# short cases, the serial module itself for the long ones):
#  - the paper's scene (coarse, to 0.5 ms), an 8-ply pack (coarse, to 0.2 ms) and a
#    4-ply perforation (-failure on -velocity 45, coarse, to its end): history.csv byte
#    for byte; summary.json byte for byte but for what the wall clock and the rank
#    count set (wall and pass times, mpi_ranks, threads, the options' -out);
#    state_hash in it (the bits of u, v, f, every point's internal state, the erosion
#    flags, the projectile, the energy accounts and the parts' own fields: a pack's
#    accounts) the serial run's;
#  - 2 ranks of 2 threads each: the pack's serial one-thread state and history;
#  - a checkpoint written at 2 ranks is the serial run's checkpoint byte for byte, and
#    restarted at 3 ranks ends on the serial run's state, history and summary (the
#    paper's scene and the 8-ply pack);
#  - a single ply struck within 1 % of its ballistic limit (coarse, fixed clamp: V50
#    16.50 m/s, docs/ballistic_limit.md; struck at 16.6 m/s) gets the same verdict and
#    state at 1, 2 and 4 ranks as on one.
#  - static amplitudes (the points' own amplitudes: state the force pass updates and the
#    replicated stable step reads at every element) at 2 and 3 ranks, and on quads at 2
#    ranks with its checkpoints the serial run's byte for byte; yarn slip at 2 ranks;
#  - -adapt over ranks is refused before the run (exit 2, naming it);
#  - a script's own loop: explicit_loop.edp's history at 2 ranks, and
#    tests/edp/scenes/api_ranks.edp (wovenffStep, wovenffForces with and without dt,
#    wovenffStableStep, wovenffSetVector "u", element fields, the energy split, each
#    state's hash) printing the same at 2 ranks as on one.
# Skipped, saying why, where the MPI module or mpirun is missing (make deps installs
# OpenMPI's libopenmpi-dev; make builds the module where mpicc is).
# test-runner: alone (its ranks use the machine's cores and wait for each other by polling:
# a test beside them would stall them; tests/run.sh runs it before the others, by itself)
set -u
tmp="${WFF_TEST_TMP:-/tmp}/distributed"
rm -rf "$tmp"; mkdir -p "$tmp"
fail=0
if [ ! -f build/mpi/wovenff.so ] || ! command -v mpirun > /dev/null; then
    echo "SKIP: no MPI module build/mpi/wovenff.so or no mpirun (OpenMPI: make deps, then make)"
    exit 0
fi
scene=freefem_scripts/ballistic_impact.edp

run() { # NAME NP (0: the serial module) ARGS...: the scene into $tmp/NAME_NP
    name=$1; np=$2; shift 2
    if [ "$np" = 0 ]; then
        set -- sh tools/ff.sh "$scene" "$@"
    else
        set -- sh tools/ff.sh -np "$np" "$scene" "$@"
    fi
    timeout -k 5 600 "$@" -threads 1 -plots 0 -vtkdt 1 -out "$tmp/${name}_$np" > "$tmp/${name}_$np.log" 2>&1
    rc=$?; echo "$rc" > "$tmp/${name}_$np.rc"; return "$rc"
}
# ran NAME NP [ARGS...]: the run's exit code, or (no run yet) run it now
ran() {
    if [ -f "$tmp/$1_$2.rc" ]; then return "$(cat "$tmp/$1_$2.rc")"; fi
    run "$@"
}
# summary.json less what the wall clock and the rank count set
summary() {
    grep -v -e '_seconds"' -e '"ns_per_element_step"' -e '"mpi_ranks"' -e '"threads"' \
        -e '"options"' "$1/summary.json"
}
hash_of() { sed -n 's/.*"state_hash": "\([0-9a-f]*\)".*/\1/p' "$1/summary.json"; }

# same NAME NP: the run at NP ranks against the serial one (NAME_0)
same() {
    name=$1; np=$2; a="$tmp/${name}_0"; b="$tmp/${name}_$np"
    if ! cmp -s "$a/history.csv" "$b/history.csv"; then
        echo "$name at $np ranks: history.csv differs from the serial run's: $(cmp "$a/history.csv" "$b/history.csv" 2>&1)"
        fail=1
    fi
    if [ "$(summary "$a")" != "$(summary "$b")" ]; then
        echo "$name at $np ranks: summary.json differs from the serial run's:"
        summary "$a" > "$tmp/a.json"; summary "$b" > "$tmp/b.json"; diff "$tmp/a.json" "$tmp/b.json" | head -6
        fail=1
    fi
    [ -n "$(hash_of "$b")" ] || { echo "$name at $np ranks: no state_hash in summary.json"; fail=1; }
}

case_at() { # NAME RANKS ARGS...
    name=$1; ranks=$2; shift 2
    ran "$name" 0 "$@" || { echo "$name serial: exit $?"; tail -3 "$tmp/${name}_0.log"; fail=1; return; }
    line="$name: state $(hash_of "$tmp/${name}_0")"
    for np in $ranks; do
        ran "$name" "$np" "$@" || { echo "$name at $np ranks: exit $?"; tail -5 "$tmp/${name}_$np.log"; fail=1; continue; }
        same "$name" "$np"
        line="$line, $np ranks $(hash_of "$tmp/${name}_$np")"
    done
    echo "$line"
}

# The runs on one process (the serial module's, one rank's) first, two at a time: a lane a
# core (the 4-ply perforation's serial run, the longest, in one; the rest in the other);
# case_at then takes each one's results (ran) and runs the ranks.
paper="-mesh coarse -tend 5e-4" pack="-mesh coarse -plies 8 -tend 2e-4"
perforation="-mesh coarse -plies 4 -failure on -velocity 45"
limit="-mesh coarse -clamp fixed -failure on -velocity 16.6"
static="-mesh coarse -tend 3e-4 -amplitudes static"
staticquad="-mesh coarse -tend 3e-4 -amplitudes static -elements quad -checkpoint 10"
slip="-mesh coarse -tend 3e-4 -set yarn_friction=0.2"
ck="-mesh coarse -tend 5e-4 -checkpoint 10"
run perforation 0 $perforation &
lane=$!
{
    run paper 0 $paper; run paper 1 $paper; run pack 0 $pack; run pack 1 $pack
    run limit 0 $limit; run static 0 $static; run staticquad 0 $staticquad; run slip 0 $slip
    run ck 0 $ck -stopafter 20
    timeout -k 5 300 sh tools/ff.sh freefem_scripts/explicit_loop.edp -n 12 -tend 1e-4 -plots 0 \
        -out "$tmp/loop_0" > "$tmp/loop_0.log" 2>&1; echo $? > "$tmp/loop_0.rc"
    timeout -k 5 300 sh tools/ff.sh tests/edp/scenes/api_ranks.edp > "$tmp/api_0.txt" 2>&1; echo $? > "$tmp/api_0.rc"
}
wait $lane

case_at paper "1 2 3 4" $paper
case_at pack "1 2 3 4" $pack
case_at perforation "2 3 4" $perforation
grep -q '"perforated": true' "$tmp/perforation_0/summary.json" \
    || { echo "the 4-ply run at 45 m/s did not perforate: the case tests no erosion"; fail=1; }
eroded=$(sed -n 's/.*"eroded_elements": \([0-9]*\).*/\1/p' "$tmp/perforation_0/summary.json")
echo "perforation: $eroded elements eroded"

# ranks x threads: 2 ranks of 2 threads each (unbound), the pack's serial one-thread answer
WFF_MPIRUN_ARGS="--bind-to none" timeout -k 5 300 sh tools/ff.sh -np 2 "$scene" -mesh coarse -plies 8 -tend 2e-4 \
    -threads 2 -plots 0 -vtkdt 1 -out "$tmp/hybrid_2" > "$tmp/hybrid_2.log" 2>&1 \
    || { echo "2 ranks x 2 threads: exit $?"; tail -5 "$tmp/hybrid_2.log"; fail=1; }
grep -q '"threads": 2' "$tmp/hybrid_2/summary.json" || { echo "2 ranks x 2 threads: the run did not take 2 threads"; fail=1; }
cmp -s "$tmp/pack_0/history.csv" "$tmp/hybrid_2/history.csv" && [ "$(hash_of "$tmp/hybrid_2")" = "$(hash_of "$tmp/pack_0")" ] \
    || { echo "2 ranks x 2 threads: the pack's state $(hash_of "$tmp/hybrid_2"), serial one thread $(hash_of "$tmp/pack_0")"; fail=1; }
echo "pack at 2 ranks x 2 threads: state $(hash_of "$tmp/hybrid_2")"

# a checkpoint at 2 ranks, restarted at 3 (the serial one: in the lanes above)
run ck 2 $ck -stopafter 20
rc=$?
[ $rc -eq 9 ] || { echo "checkpointed run at 2 ranks: exit $rc, want 9 (-stopafter)"; tail -3 "$tmp/ck_2.log"; fail=1; }
for f in "$tmp/ck_0/checkpoint/"model_*.bin; do
    cmp -s "$f" "$tmp/ck_2/checkpoint/$(basename "$f")" \
        || { echo "checkpoint $(basename "$f") at 2 ranks differs from the serial one"; fail=1; }
done
timeout -k 5 300 sh tools/ff.sh -np 3 "$scene" $ck -threads 1 -plots 0 -vtkdt 1 -restart "$tmp/ck_2" \
    > "$tmp/ck_3.log" 2>&1 || { echo "restart at 3 ranks: exit $?"; tail -5 "$tmp/ck_3.log"; fail=1; }
cmp -s "$tmp/ck_2/history.csv" "$tmp/paper_0/history.csv" \
    || { echo "checkpoint at 2 ranks, restart at 3: history.csv differs from the uninterrupted serial run's"; fail=1; }
[ "$(hash_of "$tmp/ck_2")" = "$(hash_of "$tmp/paper_0")" ] \
    || { echo "checkpoint at 2 ranks, restart at 3: state $(hash_of "$tmp/ck_2"), serial $(hash_of "$tmp/paper_0")"; fail=1; }
echo "checkpoint at 2 ranks, restarted at 3: state $(hash_of "$tmp/ck_2")"

# a pack's checkpoint at 2 ranks (the 8 plies at frame 10 of 20), restarted at 3
packck="-mesh coarse -plies 8 -tend 2e-4 -checkpoint 10"
run packck 2 $packck -stopafter 12
rc=$?
[ $rc -eq 9 ] || { echo "the pack checkpointed at 2 ranks: exit $rc, want 9 (-stopafter)"; tail -3 "$tmp/packck_2.log"; fail=1; }
timeout -k 5 300 sh tools/ff.sh -np 3 "$scene" $packck -restart "$tmp/packck_2" -threads 1 -plots 0 -vtkdt 1 \
    > "$tmp/packck_3.log" 2>&1 || { echo "the pack's restart at 3 ranks: exit $?"; tail -5 "$tmp/packck_3.log"; fail=1; }
cmp -s "$tmp/packck_2/history.csv" "$tmp/pack_0/history.csv" && [ "$(hash_of "$tmp/packck_2")" = "$(hash_of "$tmp/pack_0")" ] \
    || { echo "the pack checkpointed at 2 ranks, restarted at 3: state $(hash_of "$tmp/packck_2"), serial $(hash_of "$tmp/pack_0")"; fail=1; }
echo "the 8-ply pack checkpointed at 2 ranks, restarted at 3: state $(hash_of "$tmp/packck_2")"

# the verdict within 1 % of the ballistic limit
case_at limit "2 4" $limit
verdict() { sed -n 's/.*"verdict": "\([a-z]*\)".*/\1/p' "$1/summary.json"; }
v0=$(verdict "$tmp/limit_0")
[ -n "$v0" ] || { echo "16.6 m/s: no verdict"; fail=1; }
for np in 2 4; do
    [ "$(verdict "$tmp/limit_$np")" = "$v0" ] || { echo "16.6 m/s at $np ranks: '$(verdict "$tmp/limit_$np")', serial '$v0'"; fail=1; }
done
echo "16.6 m/s (V50 16.50 m/s on this mesh): $v0 at 1 (the serial module), 2 and 4 ranks"

# static amplitudes (triangles, then quads with checkpoints), yarn slip
case_at static "2 3" $static
case_at staticquad "2" $staticquad
n=0
for f in "$tmp/staticquad_0/checkpoint/"model_*.bin; do
    [ -f "$f" ] || continue
    n=$((n + 1))
    cmp -s "$f" "$tmp/staticquad_2/checkpoint/$(basename "$f")" \
        || { echo "static amplitudes on quads: checkpoint $(basename "$f") at 2 ranks differs from the serial one"; fail=1; }
done
[ "$n" -gt 0 ] || { echo "static amplitudes on quads: no checkpoint written"; fail=1; }
case_at slip "2" $slip

# -adapt over ranks: refused before the run, naming it
run adapt 2 -mesh coarse -tend 3e-4 -adapt 1
rc=$?
{ [ $rc -eq 2 ] && grep -q "error: ballistic_impact: -adapt 1: the model runs over 2 MPI ranks" "$tmp/adapt_2.log"; } \
    || { echo "-adapt at 2 ranks: exit $rc, want 2 with the refusal"; tail -3 "$tmp/adapt_2.log"; fail=1; }
echo "-adapt at 2 ranks: refused (exit $rc)"

# a script's own loop: explicit_loop.edp, and the API's calls one by one (on one process:
# in the lanes above)
rc=$(cat "$tmp/loop_0.rc"); [ "$rc" = 0 ] || { echo "explicit_loop at 0 ranks: exit $rc"; tail -3 "$tmp/loop_0.log"; fail=1; }
rc=$(cat "$tmp/api_0.rc"); [ "$rc" = 0 ] || { echo "api_ranks.edp at 0 ranks: exit $rc"; tail -3 "$tmp/api_0.txt"; fail=1; }
timeout -k 5 300 sh tools/ff.sh -np 2 freefem_scripts/explicit_loop.edp -n 12 -tend 1e-4 -plots 0 \
    -out "$tmp/loop_2" > "$tmp/loop_2.log" 2>&1 || { echo "explicit_loop at 2 ranks: exit $?"; tail -3 "$tmp/loop_2.log"; fail=1; }
timeout -k 5 300 sh tools/ff.sh -np 2 tests/edp/scenes/api_ranks.edp > "$tmp/api_2.txt" 2>&1 \
    || { echo "api_ranks.edp at 2 ranks: exit $?"; tail -3 "$tmp/api_2.txt"; fail=1; }
cmp -s "$tmp/loop_0/history.csv" "$tmp/loop_2/history.csv" \
    || { echo "explicit_loop at 2 ranks: history.csv differs from the serial run's"; fail=1; }
grep -q '^steps ' "$tmp/api_0.txt" || { echo "api_ranks.edp printed no state"; fail=1; }
diff "$tmp/api_0.txt" "$tmp/api_2.txt" > "$tmp/api.diff" \
    || { echo "api_ranks.edp at 2 ranks differs from one rank:"; head -6 "$tmp/api.diff"; fail=1; }
echo "a script's own loop at 2 ranks: explicit_loop.edp's history and api_ranks.edp's $(grep -c . "$tmp/api_0.txt") lines as on one rank"
exit $fail
