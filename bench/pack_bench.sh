#!/bin/sh
# The pack's cost (issue 14, item 6; make bench part 2e): 8 plies on the default
# mesh to 3 ms on 1 and 2 threads (and 2 threads spinning): wall time, ns per element-step (summary.json
# "ns_per_element_step": the loop's wall time over elements x steps, every ply's
# elements counted), the share of the step spent in ply-ply contact (the
# module's wovenffGet(md, "ply_contact_seconds") when it has the timer, in
# summary.json "ply_contact_seconds"; without it, ~ 1 - a single ply's ns per
# element-step / the pack's, both on 1 thread), the threads' speed-up (over the
# 1-thread wall), the energy error. Writes results/bench/pack.md and
# results/bench/runs/pack8_t<threads>_<passive|active>/. Not part
# of make test. Usage: sh bench/pack_bench.sh [-plies 8] [-mesh default] [-tend 3e-3]
set -u
plies=8 mesh=default tend=3e-3 out=results/bench
while [ $# -gt 0 ]; do
    [ $# -ge 2 ] || { echo "error: pack_bench: option $1 needs a value"; exit 2; }
    case "$1" in
        -plies) plies=$2 ;; -mesh) mesh=$2 ;; -tend) tend=$2 ;; -out) out=$2 ;;
        *) echo "error: pack_bench: unknown option '$1' (-plies -mesh -tend -out)"; exit 2 ;;
    esac
    shift 2
done
[ -f tools/ff.sh ] || { echo "error: pack_bench: run from the repository root"; exit 2; }
mkdir -p "$out/runs"
num() { sed -n "s/^  \"$1\": \([^,]*\),*$/\1/p" "$2/summary.json" | head -1; }
table="| threads | OpenMP wait | elements | steps | wall (s) | ns per element-step | ply contact (s) | contact share | speed-up | back-face deformation (mm) | largest energy error |
| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
# the single ply on the same mesh, 1 thread: its ns per element-step is the pack's
# without contact; 1 - that / the pack's is the pack's overhead share (contact and
# the per-ply bookkeeping), the estimate when the module has no contact timer
ref="$out/runs/pack1_t1"
rm -rf "$ref"
OMP_WAIT_POLICY=passive sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh "$mesh" -tend "$tend" -plots 0 \
    -vtkdt 1 -threads 1 -out "$ref" > "$ref.log" 2>&1 || echo "pack_bench: the single-ply run failed ($ref.log)"
ns1=$(num ns_per_element_step "$ref")
echo "one ply, 1 thread: $(num elements "$ref") elements, $ns1 ns per element-step"
wall1=""
# 1 and 2 threads as tools/ff.sh runs them (idle threads sleep: passive), then 2
# threads spinning (active): a step has several parallel passes, and waking a
# sleeping thread for each costs what the second thread saves (docs/limits.md)
for run in 1:passive 2:passive 2:active; do
    th=${run%%:*} wait=${run#*:}
    dir="$out/runs/pack${plies}_t${th}_$wait"
    rm -rf "$dir"
    start=$(date +%s.%N)
    OMP_WAIT_POLICY=$wait sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh "$mesh" -plies "$plies" \
        -tend "$tend" -plots 0 -vtkdt 1 -threads "$th" -out "$dir" > "$dir.log" 2>&1
    rc=$?
    total=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
    if [ $rc -ne 0 ] || [ ! -s "$dir/summary.json" ]; then
        echo "pack $plies plies, $th threads ($wait): FAILED (exit $rc, $dir.log)"; tail -n 3 "$dir.log"
        table="$table
| $th | $wait | failed (exit $rc) | | $total | | | | | | |"
        continue
    fi
    wall=$(num wall_seconds "$dir")
    [ "$th" = 1 ] && wall1=$wall
    row=$(awk -v th="$th" -v wait="$wait" -v el="$(num elements "$dir")" -v st="$(num steps "$dir")" -v w="$wall" \
              -v ns="$(num ns_per_element_step "$dir")" -v c="$(num ply_contact_seconds "$dir")" -v w1="$wall1" \
              -v bf="$(num back_face_deformation "$dir")" -v e="$(num max_energy_error "$dir")" -v ns1="$ns1" 'BEGIN {
        share = (c == "" ? "n/a (no timer)" : sprintf("%.1f %%", 100 * c / w))
        if (c == "" && th == 1 && ns1 != "") share = sprintf("~%.0f %% (1 - one ply'"'"'s ns / the pack'"'"'s)", 100 * (1 - ns1 / ns))
        printf "| %d | %s | %d | %d | %.1f | %.1f | %s | %s | %s | %.2f | %.3g %% |", th, wait, el, st, w, ns,
               (c == "" ? "n/a" : sprintf("%.2f", c)), share, (w1 == "" ? "" : sprintf("%.2f", w1 / w)), 1e3 * bf, 100 * e }')
    echo "$row"
    table="$table
$row"
done
{
    echo "# Pack cost ($(date -u +%Y-%m-%d): $plies plies, -mesh $mesh, -tend $tend s; sh bench/pack_bench.sh)"
    echo
    echo "$table"
} > "$out/pack.md"
cat "$out/pack.md"
