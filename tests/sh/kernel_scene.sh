#!/bin/sh
# The kernel variant through a scene: the paper's scene, coarse and short (to
# 0.3 ms), on the baseline kernels (WOVENFF_KERNEL=baseline) and on the one a
# model picks by itself (auto): summary.json names the variant, and the two
# runs give the same peak displacement, energy error and projectile velocity
# to round-off. An unknown WOVENFF_KERNEL stops the scene with exit code 4 and
# a message naming the variable and the known variants.
set -u
base="${WFF_TEST_TMP:-/tmp}/kernel_scene"
rm -rf "$base.baseline" "$base.auto" "$base.bad"
run() { # name, WOVENFF_KERNEL value
    WOVENFF_KERNEL=$2 sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse \
        -tend 0.3e-3 -vtkdt 1 -out "$base.$1" > "$base.$1.log" 2>&1
}
value() { # file, key
    sed -n "s/^  \"$2\": \([^,]*\),*\$/\1/p" "$1"
}
fail=0
run baseline baseline || { tail -5 "$base.baseline.log"; echo "baseline run failed"; exit 1; }
run auto "" || { tail -5 "$base.auto.log"; echo "auto run failed"; exit 1; }
kb=$(value "$base.baseline/summary.json" kernel)
ka=$(value "$base.auto/summary.json" kernel)
echo "kernels: baseline run $kb, auto run $ka"
[ "$kb" = '"baseline"' ] || { echo "the baseline run reports kernel $kb"; fail=1; }
case "$ka" in '"baseline"'|'"avx2"'|'"avx512"') ;; *) echo "the auto run reports kernel '$ka'"; fail=1 ;; esac
# relative 1e-9; the energy error is itself a fraction of the reference energy,
# whose round-off is ~1e-15 of it: 1e-12 absolute
for key in peak_displacement max_energy_error final_projectile_velocity steps; do
    b=$(value "$base.baseline/summary.json" $key)
    a=$(value "$base.auto/summary.json" $key)
    floor=0; [ $key = max_energy_error ] && floor=1e-12
    echo "$key: baseline $b, $ka $a"
    awk -v a="$a" -v b="$b" -v floor=$floor 'BEGIN { d = a - b; if (d < 0) d = -d; s = b < 0 ? -b : b
        exit !(a != "" && b != "" && d <= 1e-9 * s + floor) }' ||
        { echo "$key differs between the variants"; fail=1; }
done
run bad avx1024
rc=$?
[ $rc -eq 4 ] || { echo "WOVENFF_KERNEL=avx1024: exit $rc, want 4"; fail=1; }
grep -q "WOVENFF_KERNEL: kernel 'avx1024': unknown kernel variant (known: auto baseline avx2 avx512)" \
    "$base.bad.log" || { tail -3 "$base.bad.log"; echo "no clear message for an unknown kernel"; fail=1; }
exit $fail
