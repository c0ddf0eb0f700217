#!/bin/sh
# The wrinkle study (docs/wrinkling.md): the paper's ply struck at 22 and
# 60 m/s, friction clamp (the fabric draws in) against the fixed clamp (it
# cannot), on the coarse and default meshes; at the paper's Fig. 11 times
# (0.9, 1.3, 2.0 ms) the undulation near the clamp edge (tools/wrinkle.awk),
# and the picture wrinkle.png of the undulation at 2.0 ms, 60 m/s, default mesh.
#   sh tools/wrinkle_study.sh [OUT]     (OUT: a folder, default results/wrinkle_study; ~2 min)
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-results/wrinkle_study}
mkdir -p "$out" || exit 1
R=0.127   # the scene's clamp edge, m
printf '| speed (m/s) | mesh | clamp | draw-in at the clamp (mm) | t (ms) | undulation rms (um) | largest (um) | ring rms (um) | ring wavelength (mm) |\n|---|---|---|---|---|---|---|---|---|\n' > "$out/table.md"
for v in 22 60; do for mesh in coarse default; do for clamp in friction fixed; do
    run="$out/v${v}_${mesh}_$clamp"
    sh "$root/tools/ff.sh" "$root/freefem_scripts/ballistic_impact.edp" -mesh "$mesh" -clamp "$clamp" -velocity "$v" \
        -tend 2e-3 -vtkdt 1 -threads 1 -out "$run" > "$run.log" 2>&1 || { echo "$run: the run failed (see $run.log)"; exit 1; }
    slip=$(sed -n 's/.*"max_clamp_slip": \([^,]*\),.*/\1/p' "$run/summary.json")
    k=0
    for t in 0.4 0.9 1.3 2.0; do
        if [ "$k" -gt 0 ]; then
            awk -v R=$R -f "$root/tools/wrinkle.awk" "$run/contour_$k.csv" | awk -v v="$v" -v mesh="$mesh" -v clamp="$clamp" -v slip="$slip" -v t="$t" '{
                for (i = 1; i <= NF; i++) { if ($i == "rms") r[++n] = $(i + 1); if ($i == "largest") big = $(i + 1); if ($i == "wavelength") wl = $(i + 1) }
                printf "| %s | %s | %s | %.2f | %s | %.1f | %.1f | %.1f | %.1f |\n", v, mesh, clamp, slip * 1e3, t, r[1] * 1e6, big * 1e6, r[2] * 1e6, wl * 1e3 }' >> "$out/table.md"
        fi
        k=$((k + 1))
    done
done; done; done
awk -v R=$R -v out="$out/undulation_friction.csv" -f "$root/tools/wrinkle.awk" "$out/v60_default_friction/contour_3.csv" > /dev/null
awk -v R=$R -v out="$out/undulation_fixed.csv" -f "$root/tools/wrinkle.awk" "$out/v60_default_fixed/contour_3.csv" > /dev/null
gnuplot -e "friction='$out/undulation_friction.csv'; fixed='$out/undulation_fixed.csv'; out='$out/wrinkle.png'; R=$R; time_s=0.002; speed=60" \
    "$root/freefem_scripts/plots/wrinkle.gp" || exit 1
cat "$out/table.md"
echo "picture: $out/wrinkle.png"
