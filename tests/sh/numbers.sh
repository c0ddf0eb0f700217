#!/bin/sh
# Numbers at the edges of the command line and of the time loop (issue 11,
# item 4; docs/limits.md "Numbers"):
#   - an option value beyond the range of a double (1e400, -1e400, 1e-400) or
#     outside the one decimal grammar (0x10, inf, nan, 1,5) is refused (exit 2,
#     "error:" naming the option), as is a duplicated option and an option name
#     given as a value (-mesh -tend);
#   - a run that would take no step (-frame longer than -tend, -tend shorter
#     than one time step) or frames shorter than two steps is refused (exit 2),
#     without a summary;
#   - an end time that is not a whole number of frames: the last history row
#     is at the end time exactly (the model's t_stop), not rounded to whole
#     frames; a rest shorter than half a frame joins the frame before (no row
#     past -tend, no failure);
#   - history.csv's projectile_force is the frame mean: its integral over the
#     rows equals the projectile's momentum change to 1e-6 (measured 2.3e-8; the
#     last step's force, as before, was off by 1.9e-2 on this run).
set -u
tmp="${WFF_TEST_TMP:-/tmp}/numbers"
rm -rf "$tmp"
mkdir -p "$tmp"
fail=0
ballistic=freefem_scripts/ballistic_impact.edp

# refused NAME PATTERN ARGS...: exit 2, an "error:" line with PATTERN, no summary
refused() {
    name=$1; pattern=$2; shift 2
    sh tools/ff.sh "$ballistic" -mesh coarse -plots 0 -out "$tmp/$name" "$@" > "$tmp/$name.log" 2>&1
    rc=$?
    [ "$rc" -eq 2 ] || { echo "$name: exit $rc, want 2"; fail=1; }
    grep -q "^error: .*$pattern" "$tmp/$name.log" ||
        { echo "$name: no 'error: ...$pattern' line:"; tail -3 "$tmp/$name.log"; fail=1; }
    if grep -qs '"status": "ok"' "$tmp/$name/summary.json"; then
        echo "$name: summary says ok"; fail=1
    fi
}
refused overflow "-tend 1e400 is beyond the range of a double" -tend 1e400
refused overflow_neg "-standoff -1e400 is beyond the range" -standoff -1e400
refused mass_overflow "-mass 1e400 is beyond the range" -mass 1e400
refused underflow "-tend 1e-400 is below the range of a double" -tend 1e-400
refused hex "-tend '0x10' is not a number" -tend 0x10
refused inf "-mass 'inf' is not a number" -mass inf
refused nan "-velocity 'nan' is not a number" -velocity nan
refused comma "-tend '1,5e-3' is not a number" -tend 1,5e-3
refused twice "option -tend given twice" -tend 1e-4 -tend 2e-4
refused option_value "option -mesh needs a value, not the option -tend" -mesh -tend 1e-4
refused frame_long "-frame 0.001 s is longer than -tend 0.0005 s" -frame 1e-3 -tend 5e-4
refused no_step "-tend 1e-09 s is shorter than one time step" -tend 1e-9 -frame 1e-9
refused short_frame "-frame 2e-07 s is shorter than two time steps" -tend 1e-5 -frame 2e-7
echo "refused: 13 cases checked"

# a run to 0.305 ms with 10 us frames (30.5 frames)
run="$tmp/run"
sh tools/ff.sh "$ballistic" -mesh coarse -plots 0 -tend 3.05e-4 -out "$run" > "$run.log" 2>&1
rc=$?
[ "$rc" -eq 0 ] || { echo "run: exit $rc"; tail -5 "$run.log"; exit 1; }
awk -F, -v tend=3.05e-4 -v frame=1e-5 -v mass=0.104 '
    NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { t = $c["time"]; n++
      if (n > 1) { impulse += $c["projectile_force"] * (t - tp); if (t - tp > gap) gap = t - tp }
      else v0 = $c["projectile_velocity"]
      tp = t; v = $c["projectile_velocity"]; dt = $c["dt"] }
    END {
      bad = 0
      if (n != 32) { printf "history: %d rows, want 32 (frame 0, 30 whole frames, the last half frame)\n", n; bad = 1 }
      if (tp != tend) { printf "last row at %.17g s, want the end time %g s exactly (one step %g s)\n", tp, tend, dt; bad = 1 }
      else printf "last row at %.17g s: the end time %g s exactly (one step: %.3g s)\n", tp, tend, dt
      dp = mass * (v0 - v); rel = (impulse - dp) / dp; if (rel < 0) rel = -rel
      printf "integral of projectile_force %.10g N s, momentum change %.10g N s: relative difference %.2e\n", impulse, dp, rel
      if (!(dp > 0) || rel > 1e-6) { print "the integral of projectile_force is not the momentum change (tolerance 1e-6)"; bad = 1 }
      exit bad }' "$run/history.csv" || fail=1
grep -q '"status": "ok"' "$run/summary.json" || { echo "run: summary not ok"; fail=1; }

# a rest of 1e-10 s past 30 frames (once exit 4, "a model cannot go back": frame 30 had stepped
# past -tend): it joins frame 30, which ends at -tend exactly; no row past -tend
run="$tmp/rest"
sh tools/ff.sh "$ballistic" -mesh coarse -plots 0 -vtkdt 1 -tend 3.000001e-4 -out "$run" > "$run.log" 2>&1
rc=$?
[ "$rc" -eq 0 ] || { echo "rest: exit $rc"; tail -3 "$run.log"; fail=1; }
awk -F, -v tend=3.000001e-4 'NR > 1 { n++; if ($1 + 0 > tend) past = 1; t = $1 }
    END { if (n != 31 || t != tend || past) { printf "rest: %d rows (want 31), last at %.17g s (want %g), a row past it: %d\n", n, t, tend, past; exit 1 }
          printf "rest: 31 rows, the last at the end time %g s exactly\n", tend }' "$run/history.csv" || fail=1
exit $fail
