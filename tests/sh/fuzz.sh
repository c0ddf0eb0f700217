#!/bin/sh
# Fuzz test (issue 11, item 9): generated bad inputs, each checked for a clear
# message, no crash and no result that looks complete. Deterministic: awk's
# srand with fixed seeds.
#   materials  mutations of kevlar_s706.txt: a required key removed, a key
#              duplicated, a key garbled (unknown), a value replaced by a
#              non-number (0x10, inf, nan, 1e400, 1e-400, "1 2", "1e", ...), a
#              negative or huge value, the file truncated at a random byte
#   meshes     a small MSH 2.2 square: truncated at random bytes, duplicated
#              nodes (a slit), a missing node, bad numbers, z off the plane, an
#              element with a repeated node, an empty file, random bytes
#   point API  NaN and infinite arguments, amplitude changes beyond p0, strip
#              stretches outside [0.9, 1.5], negative preloads, a short array
#   options    random lines for the ballistic and strip scenes (and ten for the
#              explorer and fit scenes: a bad number), each with one
#              bad item: unknown names, missing values, option names as values,
#              huge or non-numbers, values out of range, duplicates
# Materials, meshes and point cases run in one FreeFEM process
# (tests/sh/fuzz/cases.edp, try/catch around each); option lines one process each.
# A case passes when: (materials, meshes) an error naming the file, or (the
# mutations that may be valid: a negative or huge value, a truncation after the
# last required key) acceptance with a finite point; (point) an error starting
# with the function's name; (options) exit 2 with an "error:" line naming the
# bad option or value, no summary.json saying "ok". Crash exit codes (134, 136,
# 139, 6) fail the test.
set -u
tmp="${WFF_TEST_TMP:-/tmp}/fuzz"
rm -rf "$tmp"
mkdir -p "$tmp/in"
fail=0
kevlar=freefem_scripts/materials/kevlar_s706.txt

# ---- materials: mat_<i>.txt and their kind (fail: must be refused; may: may pass)
awk -v dir="$tmp/in" -v seed=1101 '
    { line[NR] = $0 }
    END {
        srand(seed); n = NR
        split("cell rho_A p0_1 p0_2 A0_1 A0_2 k_1 k_2 kb_1 kb_2 K_I a K_d c K_s M_0 gammadot_0", req, " ")
        nb = split("abc|0x10|inf|nan|-inf|1e400|-1e400|1e-400|1 2|1e|--1|1.2.3|.|+|1,5|0x1p3|infinity|NaN|1e+|3e8x", bad, "|")
        keyline = 0
        for (i = 1; i <= n; i++) if (line[i] ~ /^[A-Za-z_0-9]+ *=/) key[++keyline] = i
        for (c = 0; c < 110; c++) {
            f = dir "/mat_" c ".txt"; kind = "fail"; m = c % 7
            if (m == 0) {          # a required key removed
                r = req[1 + int(rand() * 17)]
                for (i = 1; i <= n; i++) if (line[i] !~ ("^" r " *=")) print line[i] > f
                what = "missing " r
            } else if (m == 1) {   # a key given twice
                k = key[1 + int(rand() * keyline)]
                for (i = 1; i <= n; i++) { print line[i] > f; if (i == k) print line[i] > f }
                what = "duplicate line " k
            } else if (m == 2) {   # a garbled key (an unknown key or a bad character)
                k = key[1 + int(rand() * keyline)]
                for (i = 1; i <= n; i++) {
                    s = line[i]
                    if (i == k) { p = 1 + int(rand() * 3); s = substr(s, 1, p) (rand() < 0.5 ? "x" : "-") substr(s, p + 1) }
                    print s > f
                }
                what = "garbled key on line " k
            } else if (m == 3 || m == 4) {   # a value that is not a number
                k = key[2 + int(rand() * (keyline - 1))]   # (not cell)
                b = bad[1 + int(rand() * nb)]
                for (i = 1; i <= n; i++) {
                    s = line[i]
                    if (i == k) { split(s, kv, "="); sub(/ +$/, "", kv[1]); s = kv[1] " = " b }
                    print s > f
                }
                what = "line " k " = " b
            } else if (m == 5) {   # a negative or huge value: may be valid
                k = key[2 + int(rand() * (keyline - 1))]
                v = rand() < 0.5 ? "-1.5" : "1e300"
                for (i = 1; i <= n; i++) {
                    s = line[i]
                    if (i == k) { split(s, kv, "="); sub(/ +$/, "", kv[1]); s = kv[1] " = " v }
                    print s > f
                }
                kind = "may"; what = "line " k " = " v
            } else {               # truncated at a random byte
                text = ""; for (i = 1; i <= n; i++) text = text line[i] "\n"
                cut = 1 + int(rand() * (length(text) - 1))
                printf "%s", substr(text, 1, cut) > f
                kind = "may"; what = "truncated at byte " cut " of " length(text)
            }
            close(f)
            print c, kind, what > (dir "/materials.list")
        }
    }' "$kevlar"

# ---- meshes: mesh_<i>.msh (all must be refused)
awk -v dir="$tmp/in" -v seed=1102 '
    function square(f, dup, lose, badnum, zoff, repeat,    i, j, k, t, e, nn, ne, a, b, c, d) {
        nn = 16 + (dup ? 2 : 0)
        print "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" nn > f
        for (j = 0; j < 4; j++) for (i = 0; i < 4; i++) {
            t = 4 * j + i + 1
            x = i / 3 * 0.01; y = j / 3 * 0.01; z = (zoff && t == 6) ? 0.001 : 0
            if (badnum && t == 7) print t, "0.0x5", y, z > f; else print t, x, y, z > f
        }
        if (dup) { print 17, 1 / 3 * 0.01, 1 / 3 * 0.01, 0 > f; print 18, 2 / 3 * 0.01, 1 / 3 * 0.01, 0 > f }
        print "$EndNodes\n$Elements\n18" > f
        e = 0
        for (j = 0; j < 3; j++) for (i = 0; i < 3; i++) {
            a = 4 * j + i + 1; b = a + 1; c = a + 5; d = a + 4
            # the upper row of cells uses the copies 17, 18 of nodes 6, 7 (a slit)
            if (dup && j == 1) { if (a == 6) a = 17; if (a == 7) a = 18; if (b == 6) b = 17; if (b == 7) b = 18 }
            if (lose && a == 1) a = 99
            print ++e, 2, 2, 1, 1, a, b, c > f
            if (repeat && e == 9) print ++e, 2, 2, 1, 1, a, a, d > f; else print ++e, 2, 2, 1, 1, a, c, d > f
        }
        print "$EndElements" > f
        close(f)
    }
    BEGIN {
        srand(seed); c = 0
        good = dir "/good.msh"; square(good, 0, 0, 0, 0, 0)
        text = ""; while ((getline l < good) > 0) text = text l "\n"
        for (k = 0; k < 24; k++) {   # truncated: the last $EndElements (or more) is lost
            f = dir "/mesh_" c ".msh"; cut = 1 + int(rand() * (length(text) - 14))
            printf "%s", substr(text, 1, cut) > f; close(f)
            print c++, "fail", "truncated at byte " cut " of " length(text) > (dir "/meshes.list")
        }
        for (k = 0; k < 4; k++) {
            f = dir "/mesh_" c ".msh"
            if (k == 0) { square(f, 1, 0, 0, 0, 0); w = "duplicated nodes (a slit)" }
            if (k == 1) { square(f, 0, 1, 0, 0, 0); w = "an element uses a missing node" }
            if (k == 2) { square(f, 0, 0, 0, 1, 0); w = "a node off the z = 0 plane" }
            if (k == 3) { square(f, 0, 0, 0, 0, 1); w = "an element with a repeated node" }
            print c++, "fail", w > (dir "/meshes.list")
        }
        f = dir "/mesh_" c ".msh"; printf "" > f; close(f)
        print c++, "fail", "empty file" > (dir "/meshes.list")
        f = dir "/mesh_" c ".msh"; printf "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n" > f; close(f)
        print c++, "fail", "header only" > (dir "/meshes.list")
        for (k = 0; k < 6; k++) {   # random printable bytes
            f = dir "/mesh_" c ".msh"; s = ""
            for (i = 0; i < 200 + 50 * k; i++) s = s sprintf("%c", 32 + int(rand() * 95))
            print s > f; close(f)
            print c++, "fail", "random text" > (dir "/meshes.list")
        }
        for (k = 0; k < 4; k++) {   # a garbled line in the good file
            f = dir "/mesh_" c ".msh"; n = split(text, L, "\n"); g = 5 + int(rand() * (n - 8))
            for (i = 1; i < n; i++) print (i == g ? "zz " L[i] " qq" : L[i]) > f
            close(f)
            print c++, "fail", "garbled line " g > (dir "/meshes.list")
        }
    }'

n_mat=$(wc -l < "$tmp/in/materials.list")
n_mesh=$(wc -l < "$tmp/in/meshes.list")
sh tools/ff.sh tests/sh/fuzz/cases.edp -dir "$tmp/in" -materials "$n_mat" -meshes "$n_mesh" \
    > "$tmp/cases.log" 2>&1
rc=$?
case $rc in 0) ;; *) echo "cases.edp exited $rc (a crash?)"; tail -5 "$tmp/cases.log"; fail=1 ;; esac
grep -q "^cases done" "$tmp/cases.log" || { echo "cases.edp did not finish"; fail=1; }

# check LIST KIND_PREFIX: every case of the list has a line in cases.log that is
# an error naming the file (fail and may) or an acceptance with a finite point (may)
check_files() {
    list=$1; what=$2; ext=$3
    awk -v what="$what" -v ext="$ext" -v dir="$tmp/in" '
        FNR == NR { kind[$1] = $2; $1 = $2 = ""; desc[$0 == "" ? "" : FNR - 1] = $0; d[FNR - 1] = $0; n++; next }
        $1 == what {
            i = $2; sub(/:$/, "", i); seen[i] = 1; rest = $0; sub(/^[^:]*: /, "", rest)
            file = dir "/" (what == "material" ? "mat_" : "mesh_") i ext
            if (rest ~ /^error: /) {
                if (index(rest, file) == 0 && index(rest, "mat_" i ext) == 0 && index(rest, "mesh_" i ext) == 0) {
                    printf "%s %d (%s): the message does not name the file: %s\n", what, i, d[i], rest; bad++ }
                else errors++
            } else if (kind[i] == "may" && rest ~ /^accepted.*(finite|nodes)$/ && rest !~ /NONFINITE/) accepted++
            else { printf "%s %d (%s, must be refused): %s\n", what, i, d[i], rest; bad++ }
        }
        END {
            for (i = 0; i < n; i++) if (!(i in seen)) { printf "%s %d (%s): no result line\n", what, i, d[i]; bad++ }
            printf "%ss: %d cases, %d refused with a message naming the file, %d accepted (valid mutations), %d bad\n",
                   what, n, errors, accepted, bad
            exit bad > 0 }' "$list" "$tmp/cases.log"
}
check_files "$tmp/in/materials.list" material .txt || fail=1
check_files "$tmp/in/meshes.list" mesh .msh || fail=1
awk '$1 == "point" { n++; rest = $0; sub(/^[^:]*: /, "", rest)
                     if (rest ~ /^error: wovenff[A-Za-z]+: /) ok++; else { print "point case " $2 " " rest; bad++ } }
     END { printf "point API: %d cases, %d refused with the function named, %d bad\n", n, ok, bad
           exit (bad > 0 || n < 60) }' "$tmp/cases.log" || fail=1

# ---- option lines: one bad item after valid ones, one process each
awk -v seed=1103 '
    BEGIN {
        srand(seed)
        nb = split("-velocity -mass -preload -mu -standoff -frame -vtkdt -dtfactor -massfactor -threads -checkpoint", bnum, " ")
        ns = split("-velocity -ramp -dtfactor -frame -strain", snum, " ")
        nv = split("abc|1e400|-1e400|1e-400|0x10|inf|nan|-5|1,5|1e|--|1.2.3|1e99999|+|-0x1", bval, "|")
        ne = split("-steps -maxstrain -weftstrain -maxforce -maxshear -preload -duration", enum, " ")
        nf = split("-maxiter -n -strain -shear -noise -seed", fnum, " ")
        for (c = 0; c < 60; c++) {
            strip = c % 5 == 4
            scene = strip ? "strip_tension" : "ballistic_impact"
            base = strip ? "-family warp -plots 0 -strain 0.001" : "-mesh coarse -tend 2e-5 -plots 0"
            if (c >= 50) {   # the explorer and the fit scene: a bad number
                explorer = c % 2 == 0
                scene = explorer ? "unit_cell_explorer" : "fit_parameters"
                base = explorer ? "-path warp -steps 2 -plots 0" : "-maxiter 1 -n 2 -plots 0"
                o = explorer ? enum[1 + int(rand() * ne)] : fnum[1 + int(rand() * nf)]
                if (o == "-steps" || o == "-maxiter" || o == "-n") o = explorer ? "-maxshear" : "-noise"
                v = bval[1 + int(rand() * nv)]
                print scene "|" base " " o " " v "|" o
                continue
            }
            m = int(rand() * 6)
            if (m == 0) { o = "-" substr("qwertzuiopasdfghjk", 1 + int(rand() * 10), 3 + int(rand() * 4)); item = o " 1"; want = o }
            else if (m == 1) { o = strip ? snum[1 + int(rand() * ns)] : bnum[1 + int(rand() * nb)]; item = o; want = o }          # no value
            else if (m == 2) { o = strip ? snum[1 + int(rand() * ns)] : bnum[1 + int(rand() * nb)]
                               item = o " " (strip ? "-strain" : "-tend"); want = o }                                         # an option as value
            else if (m == 3) { o = strip ? snum[1 + int(rand() * ns)] : bnum[1 + int(rand() * nb)]
                               v = bval[1 + int(rand() * nv)]; if (v == "-5" && (o == "-standoff" || o == "-mu" || o == "-preload")) v = "nan"
                               item = o " " v; want = o }
            else if (m == 4) { o = strip ? "-strain" : "-tend"; item = o " 1e-3"; want = o }                                  # given twice
            else { o = strip ? "-family" : "-elements"; item = o " hexagon"; want = o }                                        # not a choice
            print scene "|" base " " item "|" want
        }
    }' > "$tmp/options.list"
n_opt=0; opt_bad=0
while IFS='|' read -r scene args want; do
    n_opt=$((n_opt + 1))
    out="$tmp/opt_$n_opt"
    # shellcheck disable=SC2086  # (the generated line is split into words on purpose)
    sh tools/ff.sh "freefem_scripts/$scene.edp" -out "$out" $args > "$out.log" 2>&1
    rc=$?
    why=""
    [ "$rc" -eq 2 ] || why="exit $rc, want 2"
    grep -q "^error: $scene: .*$want" "$out.log" || why="$why; no 'error: $scene: ... $want' line"
    grep -qs '"status": "ok"' "$out/summary.json" && why="$why; summary says ok"
    if [ -n "$why" ]; then
        echo "options ($scene $args): $why"; tail -2 "$out.log"; opt_bad=$((opt_bad + 1))
    fi
done < "$tmp/options.list"
echo "option lines: $n_opt cases, $((n_opt - opt_bad)) refused (exit 2, the bad option named), $opt_bad bad"
[ "$opt_bad" -eq 0 ] || fail=1
total=$((n_mat + n_mesh + n_opt + $(grep -c '^point ' "$tmp/cases.log")))
echo "fuzz: $total generated bad inputs"
[ "$total" -ge 200 ] || { echo "fewer than 200 cases"; fail=1; }
exit $fail
