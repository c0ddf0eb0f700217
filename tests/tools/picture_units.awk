# picture_units.awk — does a picture show its CSVs' numbers in their documented units?
# Used by tests/sh/picture_units.sh. Reads the trace of one gnuplot script run with
# a hook before each plot (a line "@plot", the axis labels in force as `show xlabel` etc.
# print them, lines "@format x F" with the script's tic formats, then the plot's table:
# every point as gnuplot computed it from the data, `set table`) and checks
# every data curve against the CSV files the script was given:
#   x  must be a CSV column as it is (same row for every coordinate of a point);
#   y  (or y2; a filled band's y2 - y1; an image's pixel value for the colour box)
#      must be a column, or a column plus a constant, or the sum or difference of
#      two columns of one unit (plus a constant): a quantity the CSV holds, not
#      rescaled;
# and the unit each axis label ends with, "(unit)" or "(unit, words)", must be the
# unit docs/csv_columns.md gives those columns (a unit "A or B" accepts either).
# An axis without a label passes only if its tic labels are off (a shared axis of
# stacked panels). Functions (the hook sets 7777 samples: a curve of exactly 7777
# points) and curves with no defined point are not data and are skipped.
# Variables: doc (docs/csv_columns.md), files (the CSVs, space-separated), picture
# (its name, for the messages). Prints one line per failure and a summary; exits 1
# on a failure.

function trim(s) { gsub(/^[ \t]+|[ \t]+$/, "", s); return s }
function absv(v) { return v < 0 ? -v : v }
function base(p) { sub(/^.*\//, "", p); return p }
function close_to(a, b, scale) { return absv(a - b) <= 1e-7 * (absv(a) + absv(b) + scale) + 1e-300 }
# the unit an axis label ends with: "(unit)" or "(unit, more words)"; "" if none
function label_unit(t,   i, depth, c) {
    t = trim(t)
    if (substr(t, length(t)) != ")") return ""
    depth = 0
    for (i = length(t); i > 0; i--) {
        c = substr(t, i, 1)
        if (c == ")") depth++
        else if (c == "(" && --depth == 0) break
    }
    if (i == 0) return ""
    t = substr(t, i + 1, length(t) - i - 1)
    sub(/,.*$/, "", t)
    return trim(t)
}
# does a documented unit (possibly "A or B") allow the label's unit u?
function unit_ok(doc_unit, u,   n, k, parts) {
    if (u == "") return 0
    n = split(doc_unit, parts, / or /)
    for (k = 1; k <= n; k++) if (trim(parts[k]) == u) return 1
    return 0
}
# the documented unit of column col of file f (by its name; "" if undocumented)
function doc_unit(f, col,   b, k) {
    b = base(f)
    for (k = 1; k <= ndoc; k++)
        if (col == dcol[k] && b ~ dfile[k]) return dunit[k]
    return ""
}
# the 4-digit bucket of a value (lookups try both ends of the tolerance)
function bucket(v) { return sprintf("%.3e", v) }
# rows of file fi whose column ci is within tolerance of v, into the array out; returns the count
function rows_near(fi, ci, v,   n, k, key, lst, m, r, seen) {
    n = 0
    split("", out_rows); split("", seen)
    for (k = -1; k <= 1; k++) {
        key = fi SUBSEP ci SUBSEP bucket(v * (1 + k * 1e-5))
        if (!(key in idx)) continue
        m = split(idx[key], lst, " ")
        for (r = 1; r <= m; r++)
            if (!(lst[r] in seen) && close_to(val[fi, lst[r], ci], v, 0)) { seen[lst[r]] = 1; out_rows[++n] = lst[r] }
    }
    return n
}

BEGIN {
    # the documented units: | scene | `file`, `file` | `column` | unit | meaning |
    while ((getline line < doc) > 0) {
        if (line !~ /^\| [a-z]/ || line ~ /^\| scene \|/) continue
        n = split(line, p, " \\| ")
        col = p[3]; gsub(/`/, "", col)
        u = trim(p[4])
        nf = split(p[2], fl, ", ")
        for (k = 1; k <= nf; k++) {
            f = fl[k]
            if (f ~ /PATH\.csv/) re = "^(warp|weft|equibiaxial|equalforce|shear)\\.csv$"
            else { gsub(/`/, "", f); f = trim(f); re = f; gsub(/\./, "\\.", re); gsub(/<k>/, "[0-9]+", re); re = "^" re "$" }
            ndoc++; dfile[ndoc] = re; dcol[ndoc] = col; dunit[ndoc] = u
        }
    }
    # the CSVs: a header line (or "# test T: a,b,c" blocks), then rows
    nfiles = split(files, fname, " ")
    for (fi = 1; fi <= nfiles; fi++) {
        nrow[fi] = 0; ncol[fi] = 0
        while ((getline line < fname[fi]) > 0) {
            if (line ~ /^# test [^:]*: /) { sub(/^# test [^:]*: /, "", line); ncol[fi] = split(line, cname_tmp, ","); for (c = 1; c <= ncol[fi]; c++) cname[fi, c] = cname_tmp[c]; continue }
            if (line ~ /^#/ || line ~ /^[ \t]*$/) continue
            if (ncol[fi] == 0) { ncol[fi] = split(line, cname_tmp, ","); for (c = 1; c <= ncol[fi]; c++) cname[fi, c] = cname_tmp[c]; continue }
            r = ++nrow[fi]
            m = split(line, v, ",")
            for (c = 1; c <= m && c <= ncol[fi]; c++) {
                if (v[c] !~ /^[ \t]*[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?[ \t]*$/) { num[fi, r, c] = 0; continue }
                num[fi, r, c] = 1; val[fi, r, c] = v[c] + 0
                key = fi SUBSEP c SUBSEP bucket(v[c] + 0)
                idx[key] = (key in idx) ? idx[key] " " r : r
            }
        }
        close(fname[fi])
        for (c = 1; c <= ncol[fi]; c++) cunit[fi, c] = doc_unit(fname[fi], cname[fi, c])
    }
    nplot = 0; bad = 0; ncurves = 0
}

# ---- the trace
/^@plot$/ { finish(); nplot++; lab["x"] = lab["y"] = lab["y2"] = lab["cb"] = ""; fmt["x"] = fmt["y"] = "?"; next }
/^[ \t]*(x|y|y2|cb)label is "/ {
    a = $0; sub(/^[ \t]*/, "", a); ax = a; sub(/label is .*$/, "", ax)
    sub(/^[a-z0-9]+label is "/, "", a); sub(/", offset at.*$/, "", a)
    lab[ax] = a; next
}
/^@format (x|y) / { fmt[$2] = substr($0, 11); next }
/^# Curve [0-9]+ of [0-9]+, [0-9]+ points/ { finish(); in_curve = 1; npts = 0; npoints_said = $6 + 0; title = ""; split("", colnames); next }
/^# Curve title: / && in_curve { title = substr($0, 16); next }
/^# x / && in_curve { nhead = split(substr($0, 3), colnames, " "); next }
in_curve && NF >= 3 && ($NF == "i" || $NF == "o" || $NF == "u") && $1 ~ /^[-+0-9.]/ {
    if ($NF == "u") next
    npts++
    for (k = 1; k < NF; k++) pt[npts, colnames[k]] = $k + 0
    next
}
END { finish(); if (nplot == 0) { print picture ": no plot traced (the hook did not run?)"; bad = 1 }
      printf "%s: %d data curves checked in %d plots\n", picture, ncurves, nplot
      exit bad }

# ---- one curve
function fail(msg) { printf "%s, plot %d, curve %s: %s\n", picture, nplot, title, msg; bad = 1 }
function finish(   fi, c, i, k, step, ok, n, xunits, xok, u) {
    if (!in_curve) return
    in_curve = 0
    if (npts == 0 || npoints_said == 7777) return   # no defined point, or a function
    ncurves++
    step = npts > 300 ? int(npts / 300) : 1        # a large curve: every step-th point
    nsel = 0
    for (i = 1; i <= npts; i += step) sel[++nsel] = i
    # the x axis: which columns hold every x?
    xunits = ""; found = 0; xok = 0
    for (fi = 1; fi <= nfiles; fi++) for (c = 1; c <= ncol[fi]; c++) {
        ok = 1
        for (i = 1; i <= nsel && ok; i++) {
            n = rows_near(fi, c, pt[sel[i], "x"])
            cand_n[i] = n; for (k = 1; k <= n; k++) cand[i, k] = out_rows[k]
            if (n == 0) ok = 0
        }
        if (!ok) continue
        found = 1
        u = cunit[fi, c]
        xunits = xunits (xunits == "" ? "" : ", ") cname[fi, c] " (" u ")"
        if (!axis_ok("x", u)) continue
        xok = 1
        # the other coordinates, on the rows found
        if (check_dims(fi)) { return }
    }
    if (!found) { fail("its x values (" pt[sel[1], "x"] (nsel > 1 ? ", " pt[sel[2], "x"] : "") (nsel > 2 ? ", " pt[sel[3], "x"] : "") \
                       ", ...) are no column of " files_said() ": rescaled?"); return }
    if (!xok) fail("x is " xunits "; the x label says '" lab["x"] "'" (lab["x"] == "" ? " (tic labels '" fmt["x"] "')" : ""))
    else fail("the y values are not a quantity of the y label's unit (" y_report "; y label '" lab["y"] "'" \
              (lab["y2"] != "" ? ", y2 label '" lab["y2"] "'" : "") (lab["cb"] != "" ? ", colour box '" lab["cb"] "'" : "") ")")
}
function files_said(   s, fi) { s = ""; for (fi = 1; fi <= nfiles; fi++) s = s (fi > 1 ? ", " : "") base(fname[fi]); return s }
# the axis ax may show unit u: its label's unit is u, or it is hidden (no label, no tic labels)
function axis_ok(ax, u) {
    if (lab[ax] == "") return fmt[ax] == ""
    return unit_ok(u, label_unit(lab[ax]))
}
# y (y2 too), a band's y2 - y1, an image's pixel: each a quantity of file fi on the rows
# the coordinates before it matched (a point's coordinates come from one row)
function check_dims(fi,   k) {
    y_report = ""
    split("", have)
    for (k = 1; k <= nhead; k++) have[colnames[k]] = 1
    if (("y" in have) && !quantity(fi, "y", "y")) return 0
    if (("y1" in have) && ("y2" in have) && !quantity(fi, "band", "y")) return 0
    if (("pixel" in have) && !quantity(fi, "pixel", "cb")) return 0
    return 1
}
# the value of point i for dimension dim
function pv(i, dim) { return dim == "band" ? pt[i, "y2"] - pt[i, "y1"] : pt[i, dim] }
function pscale(i, dim) { return dim == "band" ? absv(pt[i, "y2"]) + absv(pt[i, "y1"]) : 0 }
# the expression a (+ s b) + K at row r of file fi, or "" where a column is empty
function expr(fi, r, a, b, s, K) {
    if (!num[fi, r, a] || (b && !num[fi, r, b])) return ""
    return val[fi, r, a] + (b ? s * val[fi, r, b] : 0) + K
}
# does point i (the selected one) match the expression at one of its candidate rows? With
# keep, its candidates become the rows that match.
function point_ok(fi, i, dim, a, b, s, K, keep,   k, n, e, r, y, kept) {
    y = pv(sel[i], dim); n = 0
    for (k = 1; k <= cand_n[i]; k++) {
        r = cand[i, k]; e = expr(fi, r, a, b, s, K)
        if (e == "") continue
        if (close_to(y, e, pscale(sel[i], dim) + absv(K) + absv(e - K))) {
            if (!keep) return 1
            kept[++n] = r
        }
    }
    if (!keep) return 0
    for (k = 1; k <= n; k++) cand[i, k] = kept[k]
    cand_n[i] = n
    return n > 0
}
# is dimension dim a quantity of file fi (a column, + a constant, a sum or difference of two)
# of a unit the axis ax shows (y: the y or y2 label)? On success the candidate rows are
# narrowed to those that match.
function quantity(fi, dim, ax,   a, b, s, K, nk, kk, ok, i, k, r, e, u, got, what) {
    got = ""
    for (a = 1; a <= ncol[fi]; a++) for (b = 0; b <= ncol[fi]; b++) for (s = (b ? -1 : 1); s <= 1; s += 2) {
        if (b && b <= a) continue
        u = cunit[fi, a]
        if (b && cunit[fi, b] != u) continue
        nk = 0   # the constants that fit the first point (0 where it fits as it is)
        for (k = 1; k <= cand_n[1]; k++) {
            e = expr(fi, cand[1, k], a, b, s, 0)
            if (e == "") continue
            Kc[++nk] = close_to(pv(sel[1], dim), e, pscale(sel[1], dim)) ? 0 : pv(sel[1], dim) - e
        }
        for (kk = 1; kk <= nk; kk++) {
            K = Kc[kk]; ok = 1
            for (i = 1; i <= nsel && ok; i++) ok = point_ok(fi, i, dim, a, b, s, K, 0)
            if (!ok) continue
            what = cname[fi, a] (b ? (s > 0 ? " + " : " - ") cname[fi, b] : "") (K != 0 ? " + const" : "")
            if (axis_ok(ax, u) || (ax == "y" && lab["y2"] != "" && unit_ok(u, label_unit(lab["y2"])))) {
                for (i = 1; i <= nsel; i++) point_ok(fi, i, dim, a, b, s, K, 1)
                return 1
            }
            got = got (got == "" ? "" : ", ") what " (" u ")"
        }
    }
    y_report = dim ": " (got == "" ? "no column, sum or difference of two (rescaled?)" : got)
    return 0
}
