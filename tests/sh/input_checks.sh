#!/bin/sh
# What the scenes read, checked before anything is written (docs/limits.md
# "Input checks"): slips of units (issue 26) and inputs that are not regular
# files (issue 27). Every refused case must exit 2 within the time limit (a
# named pipe must not be waited on), print every pattern, and leave no results
# folder (so no lock and no marker a later run would trip on). Then: a factor
# of a few off runs; a mistyped key is named with its line and the key meant
# (scene and C reader); a script's wovenffMaterial of a named pipe fails at
# once, naming it; wovenffMaterialCheck returns the slip to a script.
# Run from the repository root (tests/run.sh does).
set -u
tmp="${WFF_TEST_TMP:-/tmp}/input_checks"
rm -rf "$tmp"
mkdir -p "$tmp"
fail=0
ballistic=freefem_scripts/ballistic_impact.edp
strip=freefem_scripts/strip_tension.edp
explorer=freefem_scripts/unit_cell_explorer.edp
kevlar=freefem_scripts/materials/kevlar_s706.txt
limit=60   # s: a refusal takes about one; a pipe waited on would take for ever

# refused NAME SCRIPT PATTERN... -- ARGS: exit 2, every PATTERN (fixed string),
# no "suggested -dtfactor", and no -out folder made
refused() {
    name=$1; script=$2; shift 2
    patterns=""
    while [ "$1" != "--" ]; do patterns="$patterns$1
"; shift; done
    shift
    out="$tmp/$name"
    timeout $limit sh tools/ff.sh "$script" -plots 0 -out "$out" "$@" > "$out.log" 2>&1 < /dev/null
    rc=$?
    ok=1
    [ "$rc" -eq 2 ] || { echo "$name: exit $rc, want 2 (124: timed out)"; ok=0; }
    printf '%s' "$patterns" | while IFS= read -r p; do
        grep -qF -- "$p" "$out.log" || { echo "$name: output lacks '$p'"; exit 1; }
    done || ok=0
    grep -q "suggested -dtfactor" "$out.log" && { echo "$name: -dtfactor advice for a unit slip"; ok=0; }
    [ -e "$out" ] && { echo "$name: the results folder $out was made (a refusal must come first)"; ok=0; }
    if [ $ok -eq 0 ]; then sed 's/^/    | /' "$out.log" | tail -6; fail=1; fi
    grep -m1 '^error: ' "$out.log" | cut -c1-220 | sed "s/^/  $name: /"
}

# ---- slips of units ------------------------------------------------------------
sed 's/^rho_A = 0.181/rho_A = 181/' "$kevlar" > "$tmp/rho_in_g.txt"
line=$(grep -n '^rho_A' "$tmp/rho_in_g.txt" | cut -d: -f1)
refused rho_in_g "$ballistic" "rho_A = 181 kg/m^2 (line $line of $tmp/rho_in_g.txt)" "~1000x" \
    "given in g/m^2?" -- -material "$tmp/rho_in_g.txt"
line=$(grep -n '^k_1' "$kevlar" | cut -d: -f1)
refused k_in_N_per_mm "$ballistic" "k_1 = 10300 N/m (line $line of $kevlar with k_1=1.03e4)" \
    "~1000x softer" "given in N/mm?" -- -set k_1=1.03e4
sed 's/^p0_1 = 0.3735e-3/p0_1 = 0.3735/; s/^p0_2 = 0.3735e-3/p0_2 = 0.3735/' "$kevlar" > "$tmp/p0_in_mm.txt"
refused p0_in_mm "$ballistic" "p0_2 = 0.3735 m (line 6 of $tmp/p0_in_mm.txt)" "yarn spacing 0.747 m" \
    "given in mm?" -- -material "$tmp/p0_in_mm.txt"
# (the strip scene has no -set: the slip goes into a copy)
sed 's/^yarn_spacing_1 = 0.747e-3/yarn_spacing_1 = 0.747/' freefem_scripts/materials/kevlar_linear.txt \
    > "$tmp/linear_mm.txt"
refused strip_spacing_in_mm "$strip" "yarn_spacing_1 = 0.747 m" "given in mm?" -- -material "$tmp/linear_mm.txt"
refused explorer_rho_in_g "$explorer" "rho_A = 181 kg/m^2" "given in g/m^2?" -- -material "$tmp/rho_in_g.txt"
refused radius_side_in_mm "$ballistic" "-radius 127 m is" "given in mm?" -- -radius 127 -side 400
refused side_in_mm "$ballistic" "-side 400 m is" "given in mm?" -- -side 400
# a FreeFEM mesh in mm (savemesh format: nv nt nbe; x y label; i j k region; i j label)
printf '4 2 4\n0 0 1\n200 0 2\n200 200 3\n0 200 4\n1 2 3 0\n1 3 4 0\n1 2 1\n2 3 2\n3 4 3\n4 1 4\n' \
    > "$tmp/square_mm.msh"
refused freefem_mesh_in_mm "$ballistic" "-mesh $tmp/square_mm.msh spans 200 m x 200 m" "~1000x" \
    "given in mm?" -- -mesh "$tmp/square_mm.msh"
# a gmsh .geo in mm, 2.5 (mm) elements: the nose would fall between nodes 2.5 m apart
geo() { # FILE SIDE SIZE: a square quarter specimen with the scene's groups
    cat > "$1" <<EOF
L = $2; lc = $3;
Point(1) = {0, 0, 0, lc}; Point(2) = {L, 0, 0, lc}; Point(3) = {L, L, 0, lc}; Point(4) = {0, L, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Curve("sym_y") = {1}; Physical Curve("sym_x") = {4}; Physical Curve("clamp") = {2, 3};
Physical Surface("fabric") = {1};
EOF
}
geo "$tmp/quarter_mm.geo" 200 10
refused gmsh_mesh_in_mm "$ballistic" "-mesh $tmp/quarter_mm.geo spans 200 m x 200 m" "given in mm?" \
    -- -mesh "$tmp/quarter_mm.geo"
geo "$tmp/quarter_coarse.geo" 0.2 0.05
refused nose_between_nodes "$ballistic" "its shortest element edge is" "nose radii" \
    "the nose would fall between nodes" -- -mesh "$tmp/quarter_coarse.geo"

# ---- inputs that are not regular files: refused, not waited on -------------------
mkfifo "$tmp/material.fifo" "$tmp/mesh.msh"
refused fifo_material "$ballistic" "-material $tmp/material.fifo is a pipe" "not a regular file: give a file" \
    -- -material "$tmp/material.fifo"
refused fifo_material_failure "$ballistic" "-material $tmp/material.fifo is a pipe" \
    -- -material "$tmp/material.fifo" -failure on
refused fifo_plymaterial "$ballistic" "-plymaterial $tmp/material.fifo is a pipe" \
    -- -plies 2 -plymaterial "$kevlar,$tmp/material.fifo"
refused fifo_mesh "$ballistic" "-mesh $tmp/mesh.msh is a pipe" -- -mesh "$tmp/mesh.msh"
refused fifo_strip "$strip" "-material $tmp/material.fifo is a pipe" -- -material "$tmp/material.fifo"
refused folder_material "$ballistic" "-material $tmp is a folder" -- -material "$tmp"
# a pipe given by path (what <(cat file) gives): read once it would be empty the second time
out="$tmp/stdin_pipe"
cat "$kevlar" | timeout $limit sh tools/ff.sh "$ballistic" -plots 0 -out "$out" -material /dev/stdin \
    > "$out.log" 2>&1
rc=$?
{ [ $rc -eq 2 ] && grep -qF -- "-material /dev/stdin is a pipe" "$out.log" && [ ! -e "$out" ]; } || {
    echo "stdin_pipe: exit $rc, want 2 with '-material /dev/stdin is a pipe' and no folder"
    tail -3 "$out.log"; fail=1; }

# ---- a factor of a few off: runs (and the mistyped key of issue 27) ---------------
out="$tmp/few"
timeout 300 sh tools/ff.sh "$ballistic" -plots 0 -out "$out" -mesh coarse -tend 2e-5 -frame 1e-5 \
    -set rho_A=0.5,k_1=3e6 > "$out.log" 2>&1
rc=$?
[ $rc -eq 0 ] || { echo "few: a factor of a few off (rho_A 0.5, k_1 3e6) exited $rc"; tail -5 "$out.log"; fail=1; }
sed 's/^k_2  =/k2 =/' "$kevlar" > "$tmp/k2.txt"
line=$(grep -n '^k2 ' "$tmp/k2.txt" | cut -d: -f1)
out="$tmp/k2"
timeout $limit sh tools/ff.sh "$ballistic" -plots 0 -out "$out" -material "$tmp/k2.txt" > "$out.log" 2>&1
rc=$?
want="$tmp/k2.txt:$line: unknown key 'k2' (line $line): did you mean 'k_2'?"
{ [ $rc -eq 4 ] && grep -qF -- "$want" "$out.log" && grep -qF -- "$want" "$out/summary.json" &&
  ! grep -q "missing key 'k_2'" "$out.log"; } ||
    { echo "k2: exit $rc, want 4 with '$want' (log and summary.json)"; tail -3 "$out.log"; fail=1; }

# ---- a script's own calls -------------------------------------------------------
cat > "$tmp/material_fifo.edp" <<EOF
load "wovenff"
string slip = wovenffMaterialCheck("$tmp/rho_in_g.txt", "");
cout << "slip: " << slip << endl;
cout << "kevlar: '" << wovenffMaterialCheck("$kevlar", "") << "'" << endl;
cout << "with a change: " << wovenffMaterialCheck("$kevlar", "k_2=1.03e4") << endl;
int h = wovenffMaterial("$tmp/material.fifo");
cout << "loaded a pipe" << endl;
EOF
timeout $limit sh tools/ff.sh "$tmp/material_fifo.edp" > "$tmp/material_fifo.log" 2>&1
rc=$?
for p in "slip: rho_A = 181 kg/m^2" "kevlar: ''" "with a change: k_2 = 10300 N/m" \
         "wovenffMaterial: material file $tmp/material.fifo is a pipe"; do
    grep -qF -- "$p" "$tmp/material_fifo.log" || { echo "material_fifo.edp: output lacks '$p'"; fail=1; }
done
[ $rc -eq 8 ] && ! grep -q "loaded a pipe" "$tmp/material_fifo.log" ||
    { echo "material_fifo.edp: exit $rc, want 8 (wovenffMaterial refuses the pipe)"; tail -3 "$tmp/material_fifo.log"; fail=1; }
exit $fail
