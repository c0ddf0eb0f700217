#!/bin/sh
# Every CSV column the scenes write, with its unit and meaning, as one markdown table
# (docs/csv_columns.md holds it; tests/sh/csv_columns.sh checks that it is what this
# prints now). The columns are read from the files the scenes write (each scene run
# briefly on the coarse mesh into a temporary folder: its CSV headers, the gnuplot
# blocks' "# test T: columns" lines) and, for the two scenes that run other scenes
# (ballistic_limit, sensitivity), from the one line of their script that writes the
# header. A cell's columns come from the cell itself (tools/cell_columns.edp: the unit-cell
# explorer's record with the cell's own units, the mechanisms of its energy split), for every
# material in freefem_scripts/materials/, so a new cell's columns appear by themselves. The
# units and meanings of the scenes' own columns are in tools/csv_units.txt; a column found
# there nowhere stops this script (exit 1), naming it.
# Usage: sh tools/csv_columns.sh [> table.md]      (from anywhere; about 10 s)
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root" || exit 1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
ff() { # NAME SCRIPT ARGS...: a scene run into $tmp/NAME
    name=$1; shift
    sh tools/ff.sh "$@" -out "$tmp/$name" > "$tmp/$name.log" 2>&1 ||
        { echo "csv_columns: sh tools/ff.sh $* failed:" >&2; tail -5 "$tmp/$name.log" >&2; exit 1; }
}
impact=freefem_scripts/ballistic_impact.edp
short="-mesh coarse -tend 2e-5 -vtkdt 1"
ff impact "$impact" -mesh coarse -tend 0.4e-3 -vtkdt 1 -plots 1
ff impact_failure "$impact" $short -failure on -plots 1
ff impact_pack "$impact" $short -plies 2 -plots 0
ff impact_backing "$impact" $short -backing clay -plots 0
ff impact_slip "$impact" -mesh coarse -tend 0.4e-3 -vtkdt 1 -plots 1 -set yarn_friction=0.2
ff strip freefem_scripts/strip_tension.edp -mesh coarse -strain 0.0005 -velocity 25 -ramp 0 -frame 1e-6 -plots 0
ff loop freefem_scripts/explicit_loop.edp -n 6 -tend 2e-5 -plots 0
ff fit freefem_scripts/fit_parameters.edp -params K_I -maxiter 1 -plots 0
: > "$tmp/cells"
for m in freefem_scripts/materials/*.txt; do
    sh tools/ff.sh tools/cell_columns.edp -material "$m" > "$tmp/cell.txt" 2>&1 ||
        { echo "csv_columns: tools/cell_columns.edp -material $m failed" >&2; cat "$tmp/cell.txt" >&2; exit 1; }
    cell=$(sed -n 's/^cell //p' "$tmp/cell.txt")
    grep -q "^$cell$" "$tmp/cells" && continue
    echo "$cell" >> "$tmp/cells"
    sed -n 's/^column //p' "$tmp/cell.txt" > "$tmp/cell_$cell.units"
    sed -n 's/^mech //p' "$tmp/cell.txt" > "$tmp/cell_$cell.mechs"
    ff "explorer_$cell" freefem_scripts/unit_cell_explorer.edp -material "$m" -steps 1 -plots 0
done
# the headers: "SCENE<TAB>FILE<TAB>column,column,..."
{
    for run in impact impact_failure impact_pack impact_slip impact_backing; do
        for f in "$tmp/$run"/*.csv; do
            printf 'ballistic_impact\t%s\t%s\n' "$(basename "$f" | sed 's/^contour_[0-9]*\.csv$/contour_<k>.csv/; s/^slip_[0-9]*\.csv$/slip_<k>.csv/')" "$(head -n 1 "$f")"
        done
    done
    for f in "$tmp"/strip/*.csv; do printf 'strip_tension\t%s\t%s\n' "$(basename "$f")" "$(head -n 1 "$f")"; done
    printf 'explicit_loop\thistory.csv\t%s\n' "$(head -n 1 "$tmp/loop/history.csv")"
    printf 'fit_parameters\tsynthetic.csv\t%s\n' "$(head -n 1 "$tmp/fit/synthetic.csv")"
    for f in fit_curves.csv fit_points.csv; do
        printf 'fit_parameters\t%s\t%s\n' "$f" "$(sed -n '1s/^# test [^:]*: //p' "$tmp/fit/$f")"
    done
    while read -r cell; do
        for f in "$tmp/explorer_$cell"/*.csv; do
            printf 'unit_cell_explorer (%s)\t%s\t%s\n' "$cell" "$(basename "$f")" "$(head -n 1 "$f")"
        done
    done < "$tmp/cells"
    # the scenes that run other scenes: their header line in the script
    limit=$(sed -n 's/^ *string text = "\(striking_velocity,[a-z_,]*\)\\n";$/\1/p' freefem_scripts/lib/wff_limit.idp)
    [ -n "$limit" ] || { echo "csv_columns: limit.csv's header not found in wff_limit.idp" >&2; exit 1; }
    printf 'ballistic_limit\tlimit.csv\t%s\n' "$limit"
    mil=$(sed -n 's/^ *string text = "\(shot,striking_velocity,[a-z_,]*\)\\n";$/\1/p' freefem_scripts/lib/wff_mil662.idp)
    [ -n "$mil" ] || { echo "csv_columns: mil662.csv's header not found in wff_mil662.idp" >&2; exit 1; }
    printf 'ballistic_limit\tmil662.csv\t%s\n' "$mil"
    for method in oat morris; do
        keys=$(sed -n "s/^ *string keyList = \"\\([a-z_,]*\\)\";.*/\\1/p; s/^ *if (morris) keyList = \"\\([a-z_,]*\\)\";.*/\\1/p" \
               freefem_scripts/lib/wff_sensitivity.idp | { [ $method = oat ] && head -n 1 || tail -n 1; })
        [ -n "$keys" ] || { echo "csv_columns: sensitivity.csv's keys not found in wff_sensitivity.idp" >&2; exit 1; }
        printf 'sensitivity (%s)\tsensitivity.csv\tinput,observable,%s\n' "$method" "$keys"
    done
} > "$tmp/headers"
# one row per (scene, column): the files that have it; unit and meaning from the cell or the table
awk -F'\t' -v tmp="$tmp" -v units=tools/csv_units.txt '
    function trim(s) { gsub(/^ +| +$/, "", s); return s }
    BEGIN {
        while ((getline line < units) > 0) {
            if (line ~ /^#/ || line !~ /\|/) continue
            split(line, p, "|"); n_dict++
            dkey[n_dict] = trim(p[1]); dunit[n_dict] = trim(p[2]); dmean[n_dict] = trim(p[3])
        }
    }
    function glob_match(pat, s,   re) { re = pat; gsub(/\./, "\\.", re); gsub(/\*/, ".*", re); gsub(/</, "\\<", re); return s ~ ("^" re "$") }
    # the first entry of the table for SCENE:FILE:COLUMN, FILE:COLUMN, SCENE:COLUMN or COLUMN
    function lookup(scene, file, col,   i, k, n, q) {
        for (i = 1; i <= n_dict; i++) {
            n = split(dkey[i], q, ":")
            if (n == 3 && !(glob_match(q[1], scene) && glob_match(q[2], file) && glob_match(q[3], col))) continue
            if (n == 2 && !((glob_match(q[1], file) || glob_match(q[1], scene)) && glob_match(q[2], col))) continue
            if (n == 1 && !glob_match(q[1], col)) continue
            found_unit = dunit[i]; found_mean = dmean[i]; return 1
        }
        return 0
    }
    {
        scene = $1; file = $2; n = split($3, cols, ",")
        if (!(scene in seen_scene)) { seen_scene[scene] = 1; order[++n_scene] = scene }
        if (!((scene, file) in seen_file)) { seen_file[scene, file] = 1; nfiles[scene]++ }
        for (c = 1; c <= n; c++)
            if (!((scene, file, cols[c]) in seen)) { seen[scene, file, cols[c]] = 1; entry[scene, ++nent[scene]] = file SUBSEP cols[c] }
    }
    END {
        # the cells: units of their columns, their mechanisms
        while ((getline cell < (tmp "/cells")) > 0) {
            f = tmp "/cell_" cell ".units"
            while ((getline line < f) > 0) { split(line, p, " "); cellunit[cell, p[1]] = p[2] }
            f = tmp "/cell_" cell ".mechs"
            while ((getline line < f) > 0) mechs = mechs " " line
        }
        bad = 0
        print "| scene | file | column | unit | meaning |"
        print "|---|---|---|---|---|"
        for (s = 1; s <= n_scene; s++) {
            scene = order[s]
            cell = ""; if (scene ~ /^unit_cell_explorer/) { cell = scene; sub(/^.*\(/, "", cell); sub(/\).*$/, "", cell) }
            nrow = 0
            for (e = 1; e <= nent[scene]; e++) {   # each (file, column): its unit and meaning
                split(entry[scene, e], fc, SUBSEP); file = fc[1]; col = fc[2]
                unit = ""; mean = ""
                if (lookup(scene, file, col)) { unit = found_unit; mean = found_mean }
                if (cell != "" && ((cell, col) in cellunit)) {
                    unit = cellunit[cell, col]
                    if (mean == "") mean = "the " cell " cell'"'"'s " (col ~ /^E_/ ? "stored energy in its mechanism " substr(col, 3) " per unit reference area" : "diagnostic or state " col)
                }
                if (unit == "" && col ~ /^energy_/) { m = substr(col, 8); if (index(mechs " ", " " m " ")) { unit = "J"; mean = "stored energy in the cell'"'"'s mechanism " m ", whole specimen" } }
                if (unit == "" || mean == "") { printf "csv_columns: %s %s: column %s has no unit or meaning (add it to tools/csv_units.txt)\n", scene, file, col > "/dev/stderr"; bad = 1; continue }
                row = col SUBSEP unit SUBSEP mean
                if (!(row in rowfiles)) { rows[++nrow] = row; rowfiles[row] = "`" file "`"; rowcount[row] = 1 }
                else { rowfiles[row] = rowfiles[row] ", `" file "`"; rowcount[row]++ }
            }
            for (r = 1; r <= nrow; r++) {
                split(rows[r], q, SUBSEP)
                where = rowfiles[rows[r]]
                if (cell != "" && rowcount[rows[r]] == nfiles[scene]) where = "`PATH.csv` (every path)"
                mean = q[3]; gsub(/\|/, "\\|", mean)
                printf "| %s | %s | `%s` | %s | %s |\n", scene, where, q[1], q[2], mean
                delete rowfiles[rows[r]]; delete rowcount[rows[r]]
            }
        }
        exit bad
    }' "$tmp/headers"
