#!/bin/sh
# wovenffV50Estimate (include/wovenff/membrane_limit.h) against the shell tool
# tools/phoenix_porwal.sh, the plain reference, for two scenes: 1 ply struck by
# the paper's ball (0.104 kg, radius 6.35 mm, clamp 0.127 m) and 12 plies struck
# by the 17-grain FSP (1.1016e-3 kg, radius 2.69875e-3 m).
#  - kevlar_linear.txt (linear_yarns: the cell's c is the tool's sqrt(S_1/rho_A)
#    exactly): the binding's V50 equals the tool's to its printed digits (5);
#  - kevlar_s706.txt (king_plain): the C core takes c from the cell's stress at
#    1 % stretch (the truss seen through the crimp), the tool k_1 p0_1/(2 p0_2);
#    V50 is proportional to c at a given Gamma, so the two scenes' ratios
#    king/linear are equal (to 1e-9) and between 0.95 and 1 (the crimp only),
#    and the binding's V50 (result array: c too) times the tool's c over its own
#    is the tool's to its printed digits; so is the clamp's speed (the ball: the
#    clamp at 20 r_p is inside the peak), and Gamma x 12 plies;
#  - the tool's -plies 12 gives what a material with rho_A and k_1 both x 12
#    gives (the pack as one membrane);
#  - 0 plies and 1.5 plies stop the script with a message naming plies.
# Run from the repository root (tests/run.sh does).
set -u
tmp="${WFF_TEST_TMP:-}"
if [ -z "$tmp" ]; then tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT; fi
dir="$tmp/v50_estimate"
mkdir -p "$dir"
fail=0
king=freefem_scripts/materials/kevlar_s706.txt linear=freefem_scripts/materials/kevlar_linear.txt
ball="-mass 0.104 -radius 6.35e-3 -opening 0.127"
fsp="-mass 1.1016e-3 -radius 2.69875e-3 -opening 0.127 -plies 12"
tool_v50() { # ARGS...: the tool's printed V50
    sh tools/phoenix_porwal.sh "$@" | awk '/^V50/ { print $2 }'
}
cat > "$dir/estimate.edp" <<EDP
load "wovenff"
cout.precision(12);
cout << "king_ball " << wovenffV50Estimate("$king", 1, 0.104, 6.35e-3, 0.127) << endl;
cout << "linear_ball " << wovenffV50Estimate("$linear", 1, 0.104, 6.35e-3, 0.127) << endl;
cout << "king_fsp " << wovenffV50Estimate("$king", 12, 1.1016e-3, 2.69875e-3, 0.127) << endl;
cout << "linear_fsp " << wovenffV50Estimate("$linear", 12, 1.1016e-3, 2.69875e-3, 0.127) << endl;
real[int] r(1);
wovenffV50Estimate("$king", 1, 0.104, 6.35e-3, 0.127, r);
cout << "king_ball_all"; for (int i = 0; i < r.n; i++) cout << " " << r[i]; cout << endl;
wovenffV50Estimate("$king", 12, 1.1016e-3, 2.69875e-3, 0.127, r);
cout << "king_fsp_all"; for (int i = 0; i < r.n; i++) cout << " " << r[i]; cout << endl;
int refused = 0;
try { wovenffV50Estimate("$linear", 0, 0.104, 6.35e-3, 0.127); } catch (...) { refused++; }
try { wovenffV50Estimate("$linear", 1.5, 0.104, 6.35e-3, 0.127); } catch (...) { refused++; }
cout << "refused " << refused << endl;
EDP
sh tools/ff.sh "$dir/estimate.edp" > "$dir/out.txt" 2>&1 || { echo "the .edp failed:"; cat "$dir/out.txt"; exit 1; }
get() { awk -v k="$1" '$1 == k { print $2 }' "$dir/out.txt"; }
# shellcheck disable=SC2086
t_ball=$(tool_v50 -material $linear $ball) t_fsp=$(tool_v50 -material $linear $fsp)
for scene in ball fsp; do
    eval "t=\$t_$scene"
    c=$(get "linear_$scene")
    # the C value printed as the tool prints (%.5g) is the tool's
    [ -n "$c" ] && [ "$(awk -v v="$c" 'BEGIN { printf "%.5g", v }')" = "$t" ] ||
        { echo "linear_yarns, $scene: wovenffV50Estimate '$c' m/s, the tool '$t' m/s"; fail=1; }
done
awk -v kb="$(get king_ball)" -v lb="$(get linear_ball)" -v kf="$(get king_fsp)" \
    -v lf="$(get linear_fsp)" 'BEGIN {
    rb = kb / lb; rf = kf / lf; d = rb / rf - 1; if (d < 0) d = -d
    if (!(d < 1e-9) || !(rb > 0.95 && rb <= 1)) {
        printf "king_plain/linear_yarns: ball %.9g, FSP %.9g (want equal, in (0.95, 1])\n", rb, rf
        exit 1 } }' || fail=1
# the tool's c, V50 and clamp speed for the S706 material
# shellcheck disable=SC2086
sh tools/phoenix_porwal.sh -material $king $ball > "$dir/tool_ball.txt"
# shellcheck disable=SC2086
sh tools/phoenix_porwal.sh -material $king $fsp > "$dir/tool_fsp.txt"
for scene in ball fsp; do
    awk -v scene="$scene" 'FNR == NR { if ($1 == "king_" scene "_all") for (i = 2; i <= NF; i++) r[i - 2] = $i; next }
        /^c / { c = $2 } /^V50/ { v = $2 } /^Gamma/ { g = $2 }
        /^clamped/ { n = split($0, w, " "); vc = w[n - 1] }
        END {
            if (!(r[5] > 0)) { print scene ": no result array"; exit 1 }
            s = c / r[5]; bad = 0
            if (sprintf("%.5g", r[0] * s) != v) { printf "%s: V50 %.9g x c %s / %.9g = %.5g, the tool %s\n", scene, r[0], c, r[5], r[0] * s, v; bad = 1 }
            if (vc != "" && sprintf("%.5g", r[4] * s) != vc) { printf "%s: clamp %.9g, rescaled %.5g, the tool %s\n", scene, r[4], r[4] * s, vc; bad = 1 }
            if ((vc == "") != (r[4] == 0)) { printf "%s: clamp speed %s here, tool \"%s\"\n", scene, r[4], vc; bad = 1 }
            if (sprintf("%.4g", r[7]) != g) { printf "%s: Gamma %.9g, the tool %s\n", scene, r[7], g; bad = 1 }
            exit bad }' "$dir/out.txt" "$dir/tool_$scene.txt" || fail=1
done
sed -e 's/^rho_A *= *[^ #]*/rho_A = 2.172/' -e 's/^k_1 *= *[^ #]*/k_1 = 1.236e8/' $king > "$dir/s706x12.txt"
# shellcheck disable=SC2086
t_scaled=$(tool_v50 -material "$dir/s706x12.txt" -mass 1.1016e-3 -radius 2.69875e-3 -opening 0.127)
# shellcheck disable=SC2086
t_plies=$(tool_v50 -material $king $fsp)
[ -n "$t_plies" ] && [ "$t_plies" = "$t_scaled" ] ||
    { echo "tool: -plies 12 gives '$t_plies' m/s, the x12 material '$t_scaled' m/s"; fail=1; }
[ "$(get refused)" = 2 ] || { echo "0 or 1.5 plies not refused:"; cat "$dir/out.txt"; fail=1; }
printf 'load "wovenff"\nreal v = wovenffV50Estimate("%s", 0, 0.104, 6.35e-3, 0.127);\n' "$linear" > "$dir/zero.edp"
sh tools/ff.sh "$dir/zero.edp" > "$dir/zero.txt" 2>&1 && { echo "0 plies: the script went on"; fail=1; }
grep -q "wovenffV50Estimate: plies = 0: must be a whole number" "$dir/zero.txt" || { echo "0 plies: no message naming plies:"; cat "$dir/zero.txt"; fail=1; }
[ $fail -eq 0 ] && echo "v50_estimate: all checks passed (linear_yarns: ball $t_ball m/s, FSP x12 $t_fsp m/s; king_plain: $(get king_ball), $(get king_fsp) m/s)"
exit $fail
