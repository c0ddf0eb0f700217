#!/bin/sh
# The teaching scene's scripted central-difference loop (explicit_loop.edp)
# against the built-in integrator on the same FreeFEM-built mesh and loading:
# the apex histories agree to 1e-10 of the peak (measured: 0, bit for bit),
# the step counts and times agree (the scene asserts equal times every frame),
# the script's own energy balance stays within 1e-4 of the energies in play
# (measured: 2.2e-5), and the files are written. Twice: the defaults
# (preload, friction, stable step every 20 steps) on a 16 x 16 quarter, and a
# stable step every step without preload or friction at 40 m/s; and a 5 m/s
# impact to 4 ms whose projectile rebounds (moves along -z in the scripted contact).
set -u
fail=0
# run NAME ARGS...: the scene into $WFF_TEST_TMP/NAME, then the checks
run() {
    name=$1; shift
    out="${WFF_TEST_TMP:-/tmp}/explicit_loop_$name"
    rm -rf "$out"
    sh tools/ff.sh freefem_scripts/explicit_loop.edp -out "$out" "$@" > "$out.log" 2>&1
    rc=$?
    tail -3 "$out.log"
    [ $rc -eq 0 ] || { echo "$name: scene exited $rc"; fail=1; return; }
    for f in history.csv summary.json; do
        [ -s "$out/$f" ] || { echo "$name: missing or empty: $f"; fail=1; }
    done
    awk -v name="$name" '
        /"max_apex_difference"/ { gsub(/[,]/, "", $2); d = $2 + 0; seen++ }
        /"max_energy_error"/ { gsub(/[,]/, "", $2); e = $2 + 0; seen++ }
        /"peak_apex"/ { gsub(/[,]/, "", $2); p = $2 + 0; seen++ }
        /"steps"/ { gsub(/[,]/, "", $2); s = $2 + 0; seen++ }
        END {
            bad = seen != 4
            if (!(d <= 1e-10)) { print name ": apex difference " d " of the peak > 1e-10"; bad = 1 }
            if (!(e < 1e-4)) { print name ": script energy error " e " >= 1e-4"; bad = 1 }
            if (!(p > 3e-3)) { print name ": peak apex " p " m: the projectile did not load the ply"; bad = 1 }
            if (!(s > 500)) { print name ": only " s " steps"; bad = 1 }
            if (!bad) print name ": " s " steps, peak " p " m, apex difference " d ", energy error " e
            exit bad }' "$out/summary.json" || fail=1
    # every frame: the CSV's two apex columns (10 digits) agree
    awk -F, -v name="$name" 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
        { n++; a = $col["apex_displacement"]; b = $col["apex_builtin"]
          if (a != b) { print name ": t = " $1 ": apex " a " (scripted) vs " b " (built-in)"; bad = 1 } }
        END { if (n < 30) { print name ": only " n " frames"; bad = 1 }; exit bad }' "$out/history.csv" || fail=1
}
run defaults -n 16 -plots 0
run every_step -n 12 -dtinterval 1 -mu 0 -preload 0 -velocity 40 -tend 2e-4 -plots 0
# a slow impact that rebounds: the scripted contact must carry a projectile moving along -z
run rebound -n 12 -velocity 5 -tend 4e-3 -plots 0
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
    { v = $col["projectile_velocity"]; if (NR == 2 || v < low) low = v }
    END { if (!(low < 0)) { print "rebound: the projectile never moved back (lowest velocity " low " m/s)"; exit 1 }
          print "rebound: lowest projectile velocity " low " m/s" }' \
    "${WFF_TEST_TMP:-/tmp}/explicit_loop_rebound/history.csv" || fail=1
exit $fail
