#!/bin/sh
# The energy balance of the ballistic scene through perforation, from every column
# of its history (issue 13, item 7): coarse mesh, -failure on, the paper's
# projectile at 25 m/s, above the coarse mesh's ballistic limit (V50 16.5 m/s,
# bench/limit_study.sh). The run must perforate, and at every history row
#  - kinetic_energy = kinetic_inplane + kinetic_transverse + kinetic_amplitude +
#    kinetic_projectile, internal_energy = the sum of the energy_<mechanism> columns;
#  - the balance recomputed from the columns, (kinetic - kinetic_stagger + impulse_stagger + stagger_shift + internal + dissipated +
#    failure + eroded - external work - the first row's total) / the impact energy,
#    equals the energy_error column (to 1e-8) and stays within 1 %.
# (The momentum balance through perforation is checked in the core, every step:
# tests/c/test_erosion.c; the 22 m/s case, which perforates too: tests/sh/failure_scene.sh.)
set -u
tmp="${WFF_TEST_TMP:-/tmp}/perforation_balance"
rm -rf "$tmp"; mkdir -p "$tmp"
v=25 mass=0.104   # m/s, kg (the paper's projectile, given to the run)
out="$tmp/run"
sh tools/ff.sh freefem_scripts/ballistic_impact.edp -mesh coarse -plots 0 -vtkdt 1 -failure on \
    -velocity $v -mass $mass -tend 10e-3 -out "$out" > "$tmp/run.log" 2>&1
rc=$?
tail -2 "$tmp/run.log"
[ $rc -eq 0 ] || { echo "exit $rc"; tail -6 "$tmp/run.log"; exit 1; }
grep -q '"perforated": true' "$out/summary.json" || { echo "not perforated at $v m/s"; exit 1; }
awk -F, -v v=$v -v mass="$mass" '
NR == 1 { for (i = 1; i <= NF; i++) { c[$i] = i; if ($i ~ /^energy_/ && $i != "energy_error") mech[++nm] = i }
          need = "kinetic_energy internal_energy dissipated_energy failure_energy eroded_energy external_work " \
                 "energy_error kinetic_inplane kinetic_transverse kinetic_amplitude kinetic_projectile kinetic_stagger stagger_shift impulse_stagger"
          n = split(need, w, " ")
          for (j = 1; j <= n; j++) if (!(w[j] in c)) { print "history.csv lacks " w[j]; bad = 1 }
          if (nm == 0) { print "history.csv has no energy_<mechanism> column"; bad = 1 }
          if (bad) exit 1
          e0 = 0.5 * mass * v * v; next }
{
    k = $c["kinetic_energy"]; ks = $c["kinetic_inplane"] + $c["kinetic_transverse"] + $c["kinetic_amplitude"] + $c["kinetic_projectile"]
    s = 0; for (j = 1; j <= nm; j++) s += $mech[j]
    tot = k - $c["kinetic_stagger"] + $c["impulse_stagger"] + $c["stagger_shift"] + $c["internal_energy"] + $c["dissipated_energy"] + $c["failure_energy"] + $c["eroded_energy"] - $c["external_work"]
    if (NR == 2) tot0 = tot
    err = (tot - tot0) / e0
    d1 = k - ks; if (d1 < 0) d1 = -d1; if (d1 > 1e-9 * e0) { print "row " NR ": kinetic " k " != its parts " ks; bad = 1 }
    d2 = $c["internal_energy"] - s; if (d2 < 0) d2 = -d2; if (d2 > 1e-9 * e0) { print "row " NR ": internal " $c["internal_energy"] " != mechanisms " s; bad = 1 }
    d3 = err - $c["energy_error"]; if (d3 < 0) d3 = -d3; if (d3 > 1e-8) { print "row " NR ": recomputed error " err " != column " $c["energy_error"]; bad = 1 }
    a = err < 0 ? -err : err; if (a > worst) { worst = a; at = $1 }
    fail = $c["failure_energy"]
}
END {
    if (NR < 3) { print "history.csv has no rows"; exit 1 }
    printf "  %d rows: largest energy error %.3g %% of the impact energy %.4g J (at %.4g ms), failure energy %.4g J\n", NR - 1, 100 * worst, e0, 1e3 * at, fail
    if (!(fail > 0)) { print "no failure energy"; bad = 1 }
    if (worst > 0.01) { print "energy error above 1 % of the impact energy"; bad = 1 }
    exit bad
}' "$out/history.csv"
