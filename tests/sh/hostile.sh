#!/bin/sh
# Hostile cases of the features added since issue 26 (issue 27 item 7): packs,
# failure, the ballistic-limit sweep, the sensitivity study, -adapt, -zonal and
# the module's functions. Each case has an automatic verdict: the exit code it
# must give and fixed strings its output must hold (the option, file or value at
# fault); a refusal must leave no results folder where the scene can refuse
# before making one. Probed for the kind, not the instance: angles reduced
# modulo 360 before any test and refused beyond +-1e6 degrees (every angle
# input); values a sweep or a study passes on are data (a tab, a newline, a
# comma in a value); speeds a sweep plans stay positive and representable;
# residual <= striking; no inf in a JSON file; a results folder is taken, never
# removed behind the user's back; a restart writes the checkpointed run's
# columns. Last: every exit code seen here, and every code a scene's header
# gives, is in docs/limits.md "Exit codes of the scenes". Runs are tiny (coarse
# mesh, -tend 2e-5 s) and the sweeps use the stand-in scene of limit_scene.sh.
# Run from the repository root (tests/run.sh does).
# test-runner: first (~23 s: one of the longest tests; tests/run.sh starts the longest first)
set -u
tmp="${WFF_TEST_TMP:-/tmp}/hostile"
rm -rf "$tmp"; mkdir -p "$tmp"
fail=0; cases=0; codes=""
ballistic=freefem_scripts/ballistic_impact.edp
sweep=freefem_scripts/ballistic_limit.edp
study=freefem_scripts/sensitivity.edp
standin=tests/edp/scenes/lambert_jonas_standin.edp
kevlar=freefem_scripts/materials/kevlar_s706.txt
short="-mesh coarse -tend 2e-5 -frame 1e-5 -plots 0"
tab=$(printf '\t')
nl="
"
start=$(date +%s)

# probe NAME WANT NOFOLDER PATTERN... -- SCRIPT ARGS...: exit WANT, every PATTERN
# (a fixed string) in the output, and NOFOLDER ("-": no check) not made
probe() {
    name=$1; want=$2; nofolder=$3; shift 3
    patterns=""
    while [ "$1" != "--" ]; do patterns="$patterns$1$nl"; shift; done
    shift
    cases=$((cases + 1))
    timeout 120 sh tools/ff.sh "$@" > "$tmp/$name.log" 2>&1 < /dev/null
    rc=$?
    codes="$codes $rc"
    ok=1
    [ "$rc" -eq "$want" ] || { echo "FAIL $name: exit $rc, want $want (124: timed out)"; ok=0; }
    printf '%s' "$patterns" | while IFS= read -r p; do
        grep -qF -- "$p" "$tmp/$name.log" || { echo "FAIL $name: output lacks '$p'"; exit 1; }
    done || ok=0
    if [ "$nofolder" != "-" ] && [ -e "$nofolder" ]; then
        echo "FAIL $name: $nofolder was made (a refusal comes before the folder)"; ok=0
    fi
    if [ $ok -eq 1 ]; then
        printf 'ok   %s: exit %s %s\n' "$name" "$rc" "$(grep -m1 '^error: ' "$tmp/$name.log" | cut -c1-150)"
    else
        sed 's/^/    | /' "$tmp/$name.log" | tail -6; fail=1
    fi
    return $((1 - ok))
}
# check NAME CONDITION-TEXT COMMAND...: a verdict on a file a case left
check() {
    name=$1; what=$2; shift 2
    cases=$((cases + 1))
    if "$@"; then echo "ok   $name: $what"; else echo "FAIL $name: $what"; fail=1; fi
}
field() { sed -n "s/^  \"$2\": \([^,]*\),*$/\1/p" "$1" | head -1; }
strict_json() { python3 -c 'import json, sys
def bad(x): raise ValueError("not JSON: " + x)
json.load(open(sys.argv[1]), parse_constant=bad)' "$1" 2>/dev/null; }
same_width() { awk -F, 'NR == 1 { n = NF } NF != n { bad = 1 } END { exit !(NR > 1 && !bad) }' "$1"; }

echo "== angles: reduced modulo 360 before any test, beyond +-1e6 degrees refused (every angle input)"
probe angle_1e30 2 "$tmp/angle_1e30" "-orientation 1e30 deg: beyond +-1e6 degrees" "give it modulo 360" \
    -- $ballistic $short -out "$tmp/angle_1e30" -orientation 1e30
probe angle_minus_1e30 2 "$tmp/angle_minus_1e30" "-orientation -1e30 deg: beyond +-1e6 degrees" \
    -- $ballistic $short -out "$tmp/angle_minus_1e30" -orientation -1e30
probe angle_1e7 2 "$tmp/angle_1e7" "-orientation 1e7 deg: beyond +-1e6 degrees" \
    -- $ballistic $short -out "$tmp/angle_1e7" -orientation 1e7
probe angle_450_runs_at_90 0 - -- $ballistic $short -out "$tmp/angle_450" -orientation 450 &&
    check angle_450_summary "summary.json says the angle used, 90, on the quarter model" \
        test "$(field "$tmp/angle_450/summary.json" orientation)/$(field "$tmp/angle_450/summary.json" symmetry)" = "90/4"
probe angle_405_quarter 2 "$tmp/angle_405" "-orientation 405 deg (45 modulo 360) with a quarter model" \
    -- $ballistic $short -out "$tmp/angle_405" -orientation 405
probe layup_1e30 2 "$tmp/layup_1e30" "-layup '0,1e30': entry 2 1e30 deg: beyond +-1e6 degrees" \
    -- $ballistic $short -out "$tmp/layup_1e30" -plies 2 -layup 0,1e30
probe layup_450 0 - -- $ballistic $short -out "$tmp/layup_450" -plies 2 -layup 0,-450 &&
    check layup_450_summary "the layup used, [0, -90], on the quarter model (-450 is -90)" \
        grep -q '"layup": \[0, -90\]' "$tmp/layup_450/summary.json"
probe sweep_layup_1e30 2 "$tmp/sweep_layup" "ballistic_limit: -layup '0,1e30': entry 2 1e30 deg: beyond +-1e6" \
    -- $sweep -scene $standin -out "$tmp/sweep_layup" -layup 0,1e30
probe fit_shear_angle 2 "$tmp/fit_shear" "-shear 1e30: must be in (0, 1.5)" \
    -- freefem_scripts/fit_parameters.edp -out "$tmp/fit_shear" -plots 0 -shear 1e30

echo "== packs"
probe plies_0 2 "$tmp/plies_0" "-plies 0: a pack holds 1 to 40 plies" -- $ballistic $short -out "$tmp/plies_0" -plies 0
probe plies_41 2 "$tmp/plies_41" "-plies 41: a pack holds 1 to 40 plies" -- $ballistic $short -out "$tmp/plies_41" -plies 41
probe layup_not_dividing 2 "$tmp/layup_nd" "-layup '0,90' has 2 entries, which do not divide -plies 3" \
    -- $ballistic $short -out "$tmp/layup_nd" -plies 3 -layup 0,90
probe plymaterial_empty_entry 2 "$tmp/plymat_empty" "-plymaterial '$kevlar,': entry 2 '': no such file" \
    -- $ballistic $short -out "$tmp/plymat_empty" -plies 2 -plymaterial "$kevlar,"
mkfifo "$tmp/m.fifo"
probe plymaterial_pipe 2 "$tmp/plymat_fifo" "-plymaterial $tmp/m.fifo is a pipe" \
    -- $ballistic $short -out "$tmp/plymat_fifo" -plies 2 -plymaterial "$kevlar,$tmp/m.fifo"
probe gap_negative 2 "$tmp/gap" "-gap -1: must be >= 0" -- $ballistic $short -out "$tmp/gap" -plies 2 -gap -1
probe pack_adapt 2 - "-adapt 5: the model is a pack of 2 plies" \
    -- $ballistic $short -out "$tmp/pack_adapt" -plies 2 -adapt 5
check pack_adapt_empty "the refused pack's folder is left empty" test -z "$(ls -A "$tmp/pack_adapt" 2>/dev/null)"
# 2 plies at 3000 m/s: perforated (the nose through both), never "not perforated"
probe pack_3000 0 - "perforated, the projectile's nose is through a hole in every ply" \
    -- $ballistic -mesh coarse -tend 3e-4 -plots 0 -out "$tmp/pack_3000" -plies 2 -failure on -velocity 3000 &&
    check pack_3000_verdict "verdict perforated, residual speed <= 3000 m/s, nose past both plies" \
        awk -v v="$(field "$tmp/pack_3000/summary.json" residual_velocity)" \
            -v tip="$(field "$tmp/pack_3000/summary.json" final_projectile_tip)" \
            -v d="$(field "$tmp/pack_3000/summary.json" verdict)" \
            'BEGIN { exit !(d == "\"perforated\"" && v > 0 && v <= 3000 && tip > 0.001) }'
# the cost limit with the step factor a pack of 8 with -failure on at 60 m/s runs with (-failure on's
# 0.6; a pack has no rule of its own since issue 26): refused before the first step (the estimate
# needs the model: its folder emptied again)
probe pack_maxsteps 2 - "dtfactor 0.6 x the stable step" "more than -maxsteps 2000" \
    -- $ballistic -mesh coarse -plots 0 -out "$tmp/pack_maxsteps" -plies 8 -failure on -velocity 60 -maxsteps 2000
check pack_maxsteps_empty "the refused run's folder is left empty" test -z "$(ls -A "$tmp/pack_maxsteps" 2>/dev/null)"
# a restart given -plies 1 (the default) writes the checkpointed run's columns, and the reverse
probe restart_base 0 - -- $ballistic -mesh coarse -tend 4e-5 -plots 0 -checkpoint 2 -out "$tmp/rs"
probe restart_plies_1 0 - -- $ballistic -mesh coarse -tend 8e-5 -plots 0 -restart "$tmp/rs" -plies 1
check restart_plies_1_columns "history.csv: every row as wide as the header (no pack columns added)" \
    same_width "$tmp/rs/history.csv"
probe restart_base_pack 0 - -- $ballistic -mesh coarse -tend 4e-5 -plots 0 -checkpoint 2 -plies 1 -out "$tmp/rp"
probe restart_without_plies 0 - -- $ballistic -mesh coarse -tend 8e-5 -plots 0 -restart "$tmp/rp"
check restart_without_plies_columns "history.csv: the pack's columns kept to the end" same_width "$tmp/rp/history.csv"

echo "== failure"
probe velocity_0_failure 0 - "stopped, the projectile moves on no more (0 m/s)" \
    -- $ballistic $short -out "$tmp/v0" -velocity 0 -failure on &&
    check velocity_0_summary "a valid run: verdict stopped, dtfactor_used 0.6, valid JSON" \
        sh -c "grep -q '\"verdict\": \"stopped\"' '$tmp/v0/summary.json' && grep -q '\"dtfactor_used\": 0.6' '$tmp/v0/summary.json'"
check velocity_0_no_division "no division by zero" sh -c "! grep -q 'Div by 0' '$tmp/velocity_0_failure.log'"
for f in "$tmp/v0/summary.json" "$tmp/pack_3000/summary.json" "$tmp/angle_450/summary.json"; do
    check "strict_json_$(basename "$(dirname "$f")")" "$f: strict JSON (no inf, no nan)" strict_json "$f"
done
probe erosion_alone 2 "$tmp/erosion" "-erosion either is a setting of -failure on" \
    -- $ballistic $short -out "$tmp/erosion" -erosion either
probe failure_choice 2 "$tmp/failure_choice" "-failure 'maybe': must be one of on|off" \
    -- $ballistic $short -out "$tmp/failure_choice" -failure maybe
probe failure_adapt 2 - "-adapt 1: the model has yarn failure" -- $ballistic $short -out "$tmp/failure_adapt" -failure on -adapt 1

echo "== adapt and zonal"
probe adapt_negative 2 "$tmp/adapt_neg" "-adapt -1: must be >= 0" -- $ballistic $short -out "$tmp/adapt_neg" -adapt -1
probe adapt_fraction 2 "$tmp/adapt_frac" "-adapt 1.5 is not a whole number" -- $ballistic $short -out "$tmp/adapt_frac" -adapt 1.5
probe adapt_pack 2 - "-adapt 1: the model is a pack of 2 plies" -- $ballistic $short -out "$tmp/adapt_pack" -adapt 1 -plies 2
probe zonal_overflow 2 "$tmp/zonal_inf" "-zonal 1e400 is beyond the range of a double" \
    -- $ballistic $short -out "$tmp/zonal_inf" -zonal 1e400
probe zonal_static 2 - "-amplitudes static with -zonal 0.05" -- $ballistic $short -out "$tmp/zonal_static" -zonal 0.05 -amplitudes static
probe zonal_pack 2 - "-zonal 0.05: the model is a pack of 2 plies" -- $ballistic $short -out "$tmp/zonal_pack" -zonal 0.05 -plies 2

echo "== the ballistic-limit sweep (the stand-in scene)"
lim="$sweep -scene $standin -plots 0 -jobs 2"
probe sweep_comma_out 0 - -- $lim -base "-law 120,0.9,2.5" -vmin 100 -vmax 200 -runs 6 -out "$tmp/sweep_a,b" &&
    check sweep_comma_csv "limit.csv: 6 fields a row, run_dir the folder with its comma (quoted)" \
        python3 -c 'import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
sys.exit(not (all(len(r) == 6 for r in rows) and rows[1][5].startswith(sys.argv[2] + "/v")))' \
            "$tmp/sweep_a,b/limit.csv" "$tmp/sweep_a,b"
check sweep_comma_json "limit.json is strict JSON" strict_json "$tmp/sweep_a,b/limit.json"
probe sweep_tab_value 2 "$tmp/sweep_tab" "-mesh 'coarse\\t-preload\\t2': a value with a control character" \
    -- $lim -mesh "coarse$tab-preload${tab}2" -out "$tmp/sweep_tab"
probe sweep_newline_value 2 "$tmp/sweep_nl" "-material 'a\\nb': a value with a control character" \
    -- $lim -material "a${nl}b" -out "$tmp/sweep_nl"
probe sweep_tab_base 2 "$tmp/sweep_tab_base" "-base '-law\\t120,0.9,2.5': a value with a control character" \
    -- $lim -base "-law${tab}120,0.9,2.5" -out "$tmp/sweep_tab_base"
probe sweep_all_undecided 5 - "no run was decided: 2 undecided at -tend" "raise -tend" \
    -- $lim -base "-law 120,0.9,2.5 -undecided 0:1000" -vmin 100 -vmax 200 -runs 8 -out "$tmp/sweep_und"
check sweep_all_undecided_speeds "no run at a negative speed (no v- folder)" \
    sh -c "! ls '$tmp/sweep_und' | grep -q '^v-'"
probe sweep_vmin_tiny 2 "$tmp/sweep_tiny" "-vmin 0.0001 m/s rounds to 0 m/s" -- $lim -vmin 0.0001 -vmax 0.004 -out "$tmp/sweep_tiny"
probe sweep_same_speed 2 "$tmp/sweep_same" "-vmin 10.001 and -vmax 10.004 m/s round to the same speed" \
    -- $lim -vmin 10.001 -vmax 10.004 -out "$tmp/sweep_same"
probe sweep_vmax_huge 2 "$tmp/sweep_huge" "-vmax 1e+300 m/s: more than 100000 m/s" -- $lim -vmax 1e300 -out "$tmp/sweep_huge"
probe sweep_floor 5 - "every run perforated (0.01 to 0.04 m/s) down to the sweep's lowest speed 0.01 m/s" \
    -- $lim -base "-law 0.001,0.9,2.5" -vmin 0.02 -vmax 0.04 -runs 8 -out "$tmp/sweep_floor"
check sweep_floor_speeds "no run below 0.01 m/s (no v0 folder)" test ! -e "$tmp/sweep_floor/v0"
probe sweep_residual_above_striking 6 - "v300: FAILED, skipped: residual speed" "above the striking speed 300 m/s" \
    -- $lim -base "-law 100,1.4,2" -vmin 50 -vmax 300 -runs 6 -out "$tmp/sweep_fast"
check sweep_residual_csv "limit.csv: no residual above its striking speed" \
    awk -F, 'NR > 1 && $2 != "" && $2 + 0 > $1 + 0 { bad = 1 } END { exit bad }' "$tmp/sweep_fast/limit.csv"
probe sweep_material_pipe 2 "$tmp/sweep_fifo" "-material $tmp/m.fifo is a pipe" -- $lim -material "$tmp/m.fifo" -out "$tmp/sweep_fifo"

echo "== the sensitivity study"
sens="$study -plots 0"
base="-mesh coarse -tend 2e-5"
probe study_range_1e400 2 "$tmp/study_inf" "-inputs 'K_I:1e-3:1e400': high 1e400 is beyond the range of a double" \
    -- $sens -base "$base" -inputs "K_I:1e-3:1e400" -out "$tmp/study_inf"
probe study_range_1e-400 2 "$tmp/study_zero" "-inputs 'velocity:1e-400:20': low 1e-400 is below the range of a double" \
    -- $sens -base "$base" -inputs "velocity:1e-400:20" -out "$tmp/study_zero"
probe study_tab_base 2 "$tmp/study_tab" "-base '-mesh\\tcoarse': a value with a control character" \
    -- $sens -base "-mesh${tab}coarse" -out "$tmp/study_tab"
mkdir -p "$tmp/study_user/runs"; echo mine > "$tmp/study_user/runs/user.txt"
probe study_user_file 2 - "results folder '$tmp/study_user' holds files that are not a wovenff run's" -- $sens -base "$base" -inputs velocity:18:26 -out "$tmp/study_user"
check study_user_file_kept "the user's file in runs/ is still there" test -s "$tmp/study_user/runs/user.txt"
probe study_refused_base 2 "$tmp/study_refused" "the base options do not run in ballistic_impact: -velocity -3: must be >= 0" \
    -- $sens -base "$base -velocity -3" -inputs velocity:18:26 -out "$tmp/study_refused"
probe study_comma_out 0 - "3 runs, 0 failed" -- $sens -base "$base" -inputs velocity:18:26 -out "$tmp/study_a,b" &&
    check study_comma_json "sensitivity.json strict JSON, sensitivity.csv rows of one width" \
        sh -c "python3 -c 'import json, sys
def bad(x): raise ValueError(x)
json.load(open(sys.argv[1]), parse_constant=bad)' '$tmp/study_a,b/sensitivity.json' && awk -F, 'NR == 1 { n = NF } NF != n { exit 1 }' '$tmp/study_a,b/sensitivity.csv'"
probe study_again 2 - "holds an earlier run's files" "-overwrite 1" -- $sens -base "$base" -inputs velocity:18:26 -out "$tmp/study_a,b"
probe study_overwrite 0 - "3 runs, 0 failed" -- $sens -base "$base" -inputs velocity:18:26 -out "$tmp/study_a,b" -overwrite 1

echo "== the module's functions"
cat > "$tmp/api.edp" <<EOF
load "wovenff"
verbosity = 0;
mesh Th = square(6, 6, [0.03 * (2 * x - 1), 0.03 * (2 * y - 1)]);
int md = wovenffModel(Th, "$kevlar", "names=1:bottom,2:right,3:top,4:left");
func int say(string what, int caught)
{
    cout << "case " << what << ": " << (caught ? "refused: " + wovenffLastError(-1) : "accepted") << endl;
    return 0;
}
int c;
c = 0; try { wovenffSet(md, "orientation", 1e30); } catch (...) { c = 1; } say("orientation_1e30", c);
c = 0; try { wovenffSet(md, "orientation", 450); } catch (...) { c = 1; } say("orientation_450", c);
wovenffPlies(md, 2, 2e-4);
c = 0; try { wovenffPlyOrientation(md, 1, -1e30); } catch (...) { c = 1; } say("ply_orientation_1e30", c);
c = 0; try { wovenffPlyOrientation(md, 2, 0); } catch (...) { c = 1; } say("ply_out_of_range", c);
real[int] vs = [100, 150, 200, 250, 300], vr = [0, 200, 160, 200, 250], fit(25);
c = 0; try { wovenffLambertJonas(vs, vr, fit); } catch (...) { c = 1; } say("residual_above_striking", c);
vr = [0, 150, 160, 200, 250];
c = 0; try { wovenffLambertJonas(vs, vr, fit); } catch (...) { c = 1; } say("residual_equal_striking", c);
vr[2] = sqrt(-1.0);
c = 0; try { wovenffLambertJonas(vs, vr, fit); } catch (...) { c = 1; } say("residual_nan", c);
cout << "case visible: " << wovenffVisible("a\\tb\\nc") << endl;
cout << "case run_tab: exit " << wovenffRun("printf\\t%s|\\t" + wovenffArg("x\\ty\\\\z"), "$tmp/api_run.log") << endl;
c = 0; try { wovenffPerforation(md); } catch (...) { c = 1; } say("perforation_no_projectile", c);
c = 0; try { wovenffPlies(md, 3, 2e-4); } catch (...) { c = 1; } say("plies_twice", c);
c = 0; try { wovenffMaterial("$tmp/m.fifo"); } catch (...) { c = 1; } say("material_pipe", c);
EOF
probe api_calls 0 - \
    "case orientation_1e30: refused: wovenffSet: orientation = 1e+30 deg: beyond +-1e6 degrees" \
    "case orientation_450: accepted" \
    "case ply_orientation_1e30: refused: wovenffPlyOrientation: ply 1 angle = -1e+30 deg: beyond +-1e6 degrees" \
    "case ply_out_of_range: refused: wovenffPlyOrientation: ply 2: the pack has plies 0 to 1" \
    "case residual_above_striking: refused: wovenffLambertJonas: Lambert-Jonas fit: run 2: residual speed 200 m/s above the striking speed 150 m/s" \
    "case residual_equal_striking: accepted" \
    "case residual_nan: refused: wovenffLambertJonas: Lambert-Jonas fit: run 3" \
    'case visible: a\tb\nc' "case run_tab: exit 0" \
    "case perforation_no_projectile: refused: wovenffPerforation: perforation: the model has no projectile" \
    "case plies_twice: refused: wovenffPlies" \
    "wovenffMaterial: material file $tmp/m.fifo is a pipe" \
    -- "$tmp/api.edp"
check api_run_tab "wovenffRun: an argument with a tab and a backslash reached the program whole" \
    test "$(cat "$tmp/api_run.log")" = "x${tab}y\\z|"

echo "== every exit code documented (docs/limits.md \"Exit codes of the scenes\")"
documented=$(awk '/^## Exit codes of the scenes/ { on = 1; next } /^## / { on = 0 }
    on && /^\| [0-9]/ { split($0, f, "|"); gsub(/ /, "", f[2]); n = split(f[2], c, ","); for (i = 1; i <= n; i++) print c[i] }' \
    docs/limits.md | sort -u | tr '\n' ' ')
for rc in $(printf '%s\n' $codes | sort -u); do
    check "exit_$rc" "exit code $rc (seen here) is documented ($documented)" \
        sh -c "printf ' %s ' '$documented' | grep -q ' $rc '"
done
for scene in freefem_scripts/*.edp; do
    # the header's "Exit" paragraph: "0 done; 2 a bad option ...", a code after "Exit", "; " or a line's indent
    heads=$(awk '/^\/\/ Exit/ { on = 1 } on && /^\/\/ [A-Z][a-z]+ / && !/^\/\/ Exit/ { on = 0 } on && !/^\/\//{ on = 0 } on' "$scene" |
            grep -oE '(Exit +|; |^// +)[0-9]+ ' | grep -oE '[0-9]+' | sort -u | tr '\n' ' ')
    check "exit_codes_$(basename "$scene" .edp)" "the header's exit codes ($heads) are documented" \
        sh -c "for c in $heads; do printf ' %s ' '$documented' | grep -q \" \$c \" || exit 1; done"
done

secs=$(($(date +%s) - start))
echo "$cases cases in $secs s; $([ $fail -eq 0 ] && echo 'all hold' || echo 'some FAILED')"
exit $fail
