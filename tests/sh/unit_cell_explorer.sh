#!/bin/sh
# Unit-cell explorer with every cell.
# king_plain, all five paths, 8 levels each (static amplitudes):
# - exit 0; each CSV has the cell's header and steps + 1 rows; every row's
#   energies per mechanism (E_*) add up to W within 1e-9 relative;
# - warp strip: crimp interchange at the end (dA1 < 0 < dA2), the weft strip
#   the mirror image, and the weft strip reaches its straight-yarn regime (end
#   stiffness dP22/dstrain above 20x the start's);
# - equal force: both yarns carry the load; shear: the spars are engaged at the
#   largest shear and carry more than at the start; a lock angle in summary.json;
# - the PNGs and summary.json exist and are not empty;
# - stiffening.png (warp and weft strips against equibiaxial) is drawn from this
#   run's three CSVs (the call gnuplot got, seen through a stand-in on PATH that
#   logs its -e settings; its four curves, traced with `set table`, are the
#   CSVs' P11 and P22 against strain), and the stiffening is there: at every
#   strain of both paths the equibiaxial P_kk is above the strip's;
# - the locking angle: summary.json's locking_angle (rad) lies within the shear
#   path, locking_angle_deg is it in degrees, the path's rows bracket it (below
#   it a spar idle, F_L1 or F_L2 = 0, above it both carrying force), it agrees
#   with the angle computed from the material file and the preloaded
#   state (the spar k engages where d_k = sqrt((lambda_l p0_l cos g)^2 + A_k^2)
#   falls to d_k0 = sqrt(p0_l^2 + A0_k^2), docs/model.md §4; the last of the two;
#   2e-5 rad: the amplitudes move a little as the engaged spar pushes),
#   and shear.png's vertical line is drawn at it (the lock= its call got);
# then the shear path with dynamic amplitudes and shear flow: gamma_f has
# flowed (0 < gamma_f < gamma), the amplitudes stay near their static balance.
# basket_2x2, warp and shear, 4 levels: its own header (F_P1, F_P2), energies
# add up, crimp interchange, the 3-D picture drawn; no stiffening.png (no
# equibiaxial path), a locking angle within the path.
# linear_yarns: no spars, locking_angle null naming why.
# linear_yarns, warp, weft and shear, 4 levels: no amplitude columns; the strip
# load is stiffness x strain (P11 = S_1 e, P22 = 0; T1 = P11 yarn_spacing_1;
# the weft P22 = S_2 e), E_shear = G gamma^2 / 2; dynamic amplitudes are
# refused with a note; no 3-D picture.
# Errors: an unknown option, a value that is not a number and an option
# without its value stop the explorer with exit 2 before anything is written;
# a binding error (dynamic amplitudes on linear_yarns, dt < 0) reaches the user.
# Run from the repository root (tests/run.sh does).
set -u
tmp="${WFF_TEST_TMP:-/tmp}"
out="$tmp/unit_cell_explorer"
rm -rf "$out" "$out".*
fail=0
# gnuplot on PATH logs each call's script and -e settings (into $out.NAME.gnuplot)
gp=$(command -v gnuplot)
mkdir -p "$tmp/uce_bin"
if [ -n "$gp" ]; then
    printf '#!/bin/sh\nprintf "%%s\\t%%s\\n" "$3" "$2" >> "${WFF_GNUPLOT_CALLS:-/dev/null}"\nexec "%s" "$@"\n' "$gp" > "$tmp/uce_bin/gnuplot"
    chmod +x "$tmp/uce_bin/gnuplot"
fi
# explore NAME ARGS...: run the explorer into $out.NAME, stop the test on a failure
explore() {
    name=$1; shift
    rm -f "$out.$name.gnuplot"
    PATH="$tmp/uce_bin:$PATH" WFF_GNUPLOT_CALLS="$out.$name.gnuplot" \
        sh tools/ff.sh freefem_scripts/unit_cell_explorer.edp -out "$out.$name" "$@" > "$out.$name.log" 2>&1
    rc=$?
    [ $rc -eq 0 ] || { echo "explorer $name exited $rc"; cat "$out.$name.log"; exit 1; }
}
# awk program prefix: the header's names to column numbers, c["name"]
hdr='NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }'
# check_csv FILE HEADER ROWS
check_csv() {
    f=$1
    [ -s "$f" ] || { echo "missing or empty: $f"; fail=1; return; }
    got=$(head -1 "$f")
    [ "$got" = "$2" ] || { echo "$f: header is '$got'"; echo "    want '$2'"; fail=1; }
    rows=$(($(wc -l < "$f") - 1))
    [ "$rows" -eq "$3" ] || { echo "$f: $rows rows, want $3"; fail=1; }
    awk -F, "$hdr"' { s = 0; for (n in c) if (n ~ /^E_/) s += $c[n]; w = $c["W"];
        d = s - w; if (d < 0) d = -d; if (d > 1e-9 * (w < 0 ? -w : w) + 1e-30) {
        printf "%s row %d: sum of E_* %.15g vs W %.15g\n", FILENAME, NR - 1, s, w; bad = 1 } }
        END { exit bad }' "$f" || fail=1
}
# expect_end FILE CONDITION MESSAGE: CONDITION (awk, columns as $c["name"]) on the last row
expect_end() {
    awk -F, "$hdr"' END { if (!('"$2"')) { print "'"$1: $3"'"; exit 1 } }' "$1" || fail=1
}

# ---- king_plain
explore king -steps 8
tail -3 "$out.king.log"
king="time,lambda1,lambda2,gamma,gamma_f,P11,P22,P12,R1,R2,dA1,dA2,dA1_static,dA2_static,T1,T2,beta1,beta2,F_I,F_L1,F_L2,M_s,W,K_amp,E_yarn_stretch,E_yarn_bending,E_compaction,E_locking,E_shear"
for p in warp weft equibiaxial; do check_csv "$out.king/$p.csv" "strain,$king" 9; done
check_csv "$out.king/equalforce.csv" "yarn_tension,$king" 9
check_csv "$out.king/shear.csv" "shear_angle,$king" 9
expect_end "$out.king/warp.csv" '$c["dA1"] < 0 && $c["dA2"] > 0' "warp strip: want dA1 < 0 < dA2 at the end"
expect_end "$out.king/weft.csv" '$c["dA2"] < 0 && $c["dA1"] > 0' "weft strip: want dA2 < 0 < dA1 at the end"
awk -F, "$hdr"' { e[NR] = $1; p[NR] = $c["P22"] } END { k0 = (p[3] - p[2]) / (e[3] - e[2]);
    k1 = (p[NR] - p[NR - 1]) / (e[NR] - e[NR - 1]); if (!(k1 > 20 * k0)) {
    print "weft strip: end stiffness " k1 " N/m not 20x the start " k0 " (still in the toe?)"; exit 1 } }' \
    "$out.king/weft.csv" || fail=1
expect_end "$out.king/equalforce.csv" \
    'sqrt(($c["T1"] - $1)^2) < 1e-6 * $1 && sqrt(($c["T2"] - $1)^2) < 1e-6 * $1' "equalforce: T1, T2 != load"
awk -F, "$hdr"' NR == 2 { f0 = $c["F_L1"] + $c["F_L2"] } { a = $c["F_L1"]; b = $c["F_L2"] }
    END { if (!(a > 0 && b > 0 && a + b > 10 * f0)) { print "shear: F_L = " a ", " b " at the end (start " f0 ")"; exit 1 } }' \
    "$out.king/shear.csv" || fail=1
for p in warp weft equibiaxial equalforce shear; do
    for f in "$p.png" "cell_$p.png"; do [ -s "$out.king/$f" ] || { echo "missing or empty: king $f"; fail=1; }; done
done
[ -s "$out.king/summary.json" ] || { echo "missing or empty: summary.json"; fail=1; }
grep -q '"lock_angle_deg": [0-9]' "$out.king/summary.json" || { echo "summary.json: no lock angle"; fail=1; }

# stiffening.png: drawn from this run's strips and equibiaxial CSVs, the stiffening there
[ -s "$out.king/stiffening.png" ] || { echo "missing or empty: king stiffening.png"; fail=1; }
stiff=$(awk -F'\t' '$1 ~ /explorer_stiffening[.]gp$/ { print $2 }' "$out.king.gnuplot")
for f in warp weft equi; do
    want=$out.king/$f.csv; [ $f = equi ] && want=$out.king/equibiaxial.csv
    printf '%s\n' "$stiff" | grep -qF "$f='$want'" || { echo "stiffening.png: not drawn from $want ($stiff)"; fail=1; }
done
if [ -n "$gp" ] && [ -n "$stiff" ]; then
    # its curves as drawn (set table before each plot), against the CSVs' (strain, P_kk)
    sed 's/^\( *\)plot /\1unset table; print $T; set table $T; plot /' freefem_scripts/plots/explorer_stiffening.gp > "$tmp/uce_stiff.gp"
    "$gp" -e "$stiff; out='$tmp/uce_stiff.png'" -e 'set print $T; print ""; unset print' "$tmp/uce_stiff.gp" \
        -e 'unset table; print $T' 2> "$tmp/uce_stiff.txt" >/dev/null
    for pair in "warp P11 0" "equibiaxial P11 1" "weft P22 2" "equibiaxial P22 3"; do
        set -- $pair
        # curve $3 of the trace (in drawing order) against column $2 of $1.csv
        awk -F, -v want="$3" -v col="$2" -v csv="$out.king/$1.csv" '
            BEGIN { while ((getline l < csv) > 0) { n = split(l, v, ","); if (!h) { for (i = 1; i <= n; i++) c[v[i]] = i; h = 1; continue }
                                                    rows++; x[rows] = v[1]; y[rows] = v[c[col]] } }
            /^# Curve [0-9]/ { k++ } /^#/ { next } split($0, w, " ") < 3 { next }
            k - 1 == want { m++; d = w[2] - y[m]; if (d < 0) d = -d; e = w[1] - x[m]; if (e < 0) e = -e   # (6 digits: %g)
                            if (m > rows || d > 1e-5 * (y[m] < 0 ? -y[m] : y[m]) + 1e-9 || e > 1e-5 * x[m] + 1e-12) bad = 1 }
            END { if (bad || m != rows) { printf "stiffening.png curve %d: not %s of %s (%d points, %d rows)\n", want, col, csv, m, rows; exit 1 } }' \
            "$tmp/uce_stiff.txt" || fail=1
    done
fi
# the stiffening: at each strain both paths reach, equibiaxial P_kk above the strip's (linear between levels)
for pair in "warp P11" "weft P22"; do
    set -- $pair
    awk -F, -v col="$2" -v strip="$out.king/$1.csv" -v equi="$out.king/equibiaxial.csv" '
        function load(f, X, Y,   l, v, n, i, c, h, r) { while ((getline l < f) > 0) { n = split(l, v, ",")
            if (!h) { for (i = 1; i <= n; i++) c[v[i]] = i; h = 1; continue } r++; X[r] = v[1]; Y[r] = v[c[col]] } return r }
        BEGIN { ns = load(strip, sx, sy); ne = load(equi, ex, ey)
            for (j = 2; j <= ne; j++) for (i = 2; i <= ns; i++) if (sx[i - 1] <= ex[j] && ex[j] <= sx[i]) {
                s = sy[i - 1] + (sy[i] - sy[i - 1]) * (ex[j] - sx[i - 1]) / (sx[i] - sx[i - 1]); n++
                if (!(ey[j] > s)) { printf "%s: equibiaxial %s %g not above the strip'"'"'s %g at strain %g\n", strip, col, ey[j], s, ex[j]; bad = 1 }
                if (ex[j] == ex[ne] || j == ne) last = sprintf("%s at strain %g: equibiaxial %g, strip %g N/m", col, ex[j], ey[j], s) }
            if (n < 3) { print strip ": fewer than 3 strains shared with the equibiaxial path"; bad = 1 }
            print "stiffening, " last; exit bad }' || fail=1
done

# the locking angle: within the path, bracketed by its rows, the material's, on shear.png
lock=$(sed -n 's/^  "locking_angle": \([0-9.e+-]*\),$/\1/p' "$out.king/summary.json")
lockdeg=$(sed -n 's/^  "locking_angle_deg": \([0-9.e+-]*\),$/\1/p' "$out.king/summary.json")
mat=freefem_scripts/materials/kevlar_s706.txt
awk -F, -v g="$lock" -v gd="$lockdeg" -v mat="$mat" "$hdr"'
    { q[NR - 1] = $1; engaged[NR - 1] = $c["F_L1"] > 0 && $c["F_L2"] > 0
      if (NR == 2) { l1 = $c["lambda1"]; l2 = $c["lambda2"]; a1 = $c["dA1"]; a2 = $c["dA2"] } n = NR - 1 }
    END {
        if (g == "" || !(g > 0 && g <= q[n])) { print "shear: locking_angle \"" g "\" not within the path (0, " q[n] "]"; exit 1 }
        if (gd == "" || (gd - g * 180 / atan2(0, -1))^2 > (1e-9 * gd)^2) { print "shear: locking_angle_deg " gd " is not " g " rad"; exit 1 }
        for (j = 1; j <= n; j++) if (q[j - 1] < g && g <= q[j] && (engaged[j - 1] || !engaged[j])) {
            print "shear: rows at " q[j - 1] " and " q[j] " rad do not bracket the locking angle " g " (spars engaged: " engaged[j - 1] ", " engaged[j] ")"; exit 1 }
        while ((getline line < mat) > 0) { split(line, w, " "); if (w[2] == "=") m[w[1]] = w[3] + 0 }
        # spar k engages where its length d_k = sqrt((lambda_l p0_l cos g)^2 + A_k^2) falls to
        # d_k0 = sqrt(p0_l^2 + A0_k^2) (lengths kept by the picture frame; the amplitudes at the preload)
        A1 = m["A0_1"] + a1; A2 = m["A0_2"] + a2
        c1 = sqrt(m["p0_2"]^2 + m["A0_1"]^2 - A1^2) / (l2 * m["p0_2"])
        c2 = sqrt(m["p0_1"]^2 + m["A0_2"]^2 - A2^2) / (l1 * m["p0_1"])
        g1 = c1 >= 1 ? 0 : atan2(sqrt(1 - c1^2), c1); g2 = c2 >= 1 ? 0 : atan2(sqrt(1 - c2^2), c2)
        want = g1 > g2 ? g1 : g2
        printf "locking angle %.6f rad (%.3f deg), from the material %.6f (warp spar %.6f, weft spar %.6f): %.1e rad apart\n", \
            g, gd, want, g1, g2, g - want
        if ((g - want)^2 > 2e-5^2) { print "shear: the locking angle is not the material'"'"'s"; exit 1 } }' \
    "$out.king/shear.csv" || fail=1
shearvars=$(awk -F'\t' '$1 ~ /explorer_path[.]gp$/ && $2 ~ /path='"'"'shear'"'"'/ { print $2 }' "$out.king.gnuplot")
printf '%s\n' "$shearvars" | grep -qF "lock=$lock" || { echo "shear.png: not given lock=$lock (${shearvars##*; })"; fail=1; }

explore dyn -path shear -steps 6 -amplitudes dynamic -dynamic 1 -plots 0
check_csv "$out.dyn/shear.csv" "shear_angle,$king" 7
expect_end "$out.dyn/shear.csv" '$c["gamma_f"] > 0 && $c["gamma_f"] < $c["gamma"]' "dynamic shear: want 0 < gamma_f < gamma"
expect_end "$out.dyn/shear.csv" 'sqrt(($c["dA1"] - $c["dA1_static"])^2) < 2e-6 && sqrt(($c["dA2"] - $c["dA2_static"])^2) < 2e-6' \
    "dynamic shear: amplitudes far from the static balance"
grep -q '"amplitude_substeps": [1-9]' "$out.dyn/summary.json" || { echo "dynamic: no amplitude steps"; fail=1; }

# ---- basket_2x2
explore basket -material freefem_scripts/materials/kevlar_basket.txt -path warp,shear -steps 4
basket="time,lambda1,lambda2,gamma,gamma_f,P11,P22,P12,R1,R2,dA1,dA2,dA1_static,dA2_static,T1,T2,beta1,beta2,F_I,F_L1,F_L2,F_P1,F_P2,M_s,W,K_amp,E_yarn_stretch,E_yarn_bending,E_compaction,E_locking,E_shear"
check_csv "$out.basket/warp.csv" "strain,$basket" 5
check_csv "$out.basket/shear.csv" "shear_angle,$basket" 5
expect_end "$out.basket/warp.csv" '$c["dA1"] < 0 && $c["dA2"] > 0' "basket warp strip: want dA1 < 0 < dA2"
for f in warp.png cell_warp.png shear.png cell_shear.png; do
    [ -s "$out.basket/$f" ] || { echo "missing or empty: basket $f"; fail=1; }
done
[ -e "$out.basket/stiffening.png" ] && { echo "basket: stiffening.png without an equibiaxial path"; fail=1; }
grep -q '^  "locking_angle": [0-9]' "$out.basket/summary.json" || { echo "basket: no locking_angle"; fail=1; }

# ---- linear_yarns (S_1 = S_2 = 5.15e6 N/m, G = 179 N/m, yarn_spacing_1 = 0.747e-3 m)
explore linear -material freefem_scripts/materials/kevlar_linear.txt -path warp,weft,shear -steps 4 \
    -amplitudes dynamic
linear="time,lambda1,lambda2,gamma,gamma_f,P11,P22,P12,T1,T2,W,E_yarn_stretch,E_shear"
for p in warp weft; do check_csv "$out.linear/$p.csv" "strain,$linear" 5; done
check_csv "$out.linear/shear.csv" "shear_angle,$linear" 5
awk -F, "$hdr"' { e = $1; if (sqrt(($c["P11"] - 5.15e6 * e)^2) > 1e-9 * 5.15e6 * e || $c["P22"] != 0 ||
    sqrt(($c["T1"] - $c["P11"] * 0.747e-3)^2) > 1e-9 * $c["P11"] * 0.747e-3) {
    print "linear warp strip at " e ": P11 = " $c["P11"] ", P22 = " $c["P22"] ", T1 = " $c["T1"]; bad = 1 } }
    END { exit bad }' "$out.linear/warp.csv" || fail=1
awk -F, "$hdr"' { e = $1; if (sqrt(($c["P22"] - 5.15e6 * e)^2) > 1e-9 * 5.15e6 * e) {
    print "linear weft strip at " e ": P22 = " $c["P22"]; bad = 1 } } END { exit bad }' "$out.linear/weft.csv" || fail=1
awk -F, "$hdr"' { g = $c["gamma"]; w = 0.5 * 179 * g * g; if (sqrt(($c["E_shear"] - w)^2) > 1e-9 * w + 1e-12) {
    print "linear shear at " g ": E_shear = " $c["E_shear"] ", G g^2/2 = " w; bad = 1 } } END { exit bad }' \
    "$out.linear/shear.csv" || fail=1
grep -q "cell linear_yarns has no crimp amplitudes" "$out.linear.log" || { echo "linear: no note on the amplitudes"; fail=1; }
[ -s "$out.linear/warp.png" ] || { echo "missing or empty: linear warp.png"; fail=1; }
[ -e "$out.linear/cell_warp.png" ] && { echo "linear: a 3-D picture without a reference geometry"; fail=1; }
grep -q '^  "locking_angle": null,' "$out.linear/summary.json" && grep -q '"locking_note": "the cell linear_yarns has no locking spars' "$out.linear/summary.json" \
    || { echo "linear: locking_angle not null with its reason"; fail=1; }

# ---- errors: exit 2 naming the option, nothing written
# bad NAME PATTERN ARGS...
bad() {
    name=$1; pattern=$2; shift 2
    sh tools/ff.sh freefem_scripts/unit_cell_explorer.edp -out "$out.bad" "$@" > "$out.$name.log" 2>&1
    rc=$?
    [ $rc -eq 2 ] || { echo "explorer $name: exit $rc, want 2"; fail=1; }
    grep -qF -- "$pattern" "$out.$name.log" || { echo "explorer $name: no '$pattern':"; head -3 "$out.$name.log"; fail=1; }
    [ -e "$out.bad" ] && { echo "explorer $name: wrote $out.bad"; rm -rf "$out.bad"; fail=1; }
}
bad unknown "error: unit_cell_explorer: unknown option '-bogus'" -bogus 1
bad notnumber "error: unit_cell_explorer: -steps 'abc' is not a number" -steps abc
bad novalue "error: unit_cell_explorer: option -steps needs a value" -plots 0 -steps
bad strain_beyond_model "error: unit_cell_explorer: -maxstrain 0.6: must be in (0, 0.5]" -maxstrain 0.6

# binding errors reach the script user
# binding NAME PATTERN LINE: a two-line script (load, F, dA, state) plus LINE, exit 8
binding() {
    { echo 'load "wovenff"'; echo 'real[int] F = [1.01, 0, 0, 1, 0, 0], dA = [0, 0], st(6), o(1);'; echo "$3"; } \
        > "$tmp/uce_$1.edp"
    st=0
    sh tools/ff.sh "$tmp/uce_$1.edp" > "$tmp/uce_$1.log" 2>&1 || st=$?
    if [ $st -ne 8 ] || ! grep -qF "$2" "$tmp/uce_$1.log"; then
        echo "binding $1: exit $st"; cat "$tmp/uce_$1.log"; fail=1
    fi
}
binding bad_dt "wovenffPointStep: dt = -1e-06 must be >= 0" \
    'wovenffPointStep("freefem_scripts/materials/kevlar_s706.txt", F, dA, 0.0, -1e-6, o);'
binding no_amplitudes "wovenffPathSegment: cell 'linear_yarns' (material freefem_scripts/materials/kevlar_linear.txt) has no amplitudes" \
    'st = 0; wovenffPathSegment("freefem_scripts/materials/kevlar_linear.txt", F, F, 1e-6, 1, 0, st);'
binding state_size "wovenffPathSegment: state must have 6 entries" \
    'real[int] s2(5); wovenffPathSegment("freefem_scripts/materials/kevlar_s706.txt", F, F, 1e-6, 1, 0, s2);'
exit $fail
