# wff_observables.awk — the numbers a sensitivity study reads from one run of
# the ballistic scene (its summary.json, history.csv and profiles.csv), as
# "key value" lines. Knows those files' layout, nothing of the study.
#   awk -f wff_observables.awk -v profile_time=2e-3 summary.json profiles.csv
#     status, error, peak_displacement, peak_time, max_clamp_slip,
#     final_projectile_velocity (summary.json, SI units);
#     profile_time (the profile time nearest profile_time, s) and
#     warp_weft_difference: max over the profile of |warp - weft| divided by
#     the apex displacement at that time (-)
#   awk -F, -f wff_observables.awk -v mode=l2 a/history.csv b/history.csv ref/history.csv
#     apex_l2: ||apex_a - apex_b|| / ||apex_ref|| over the rows the three share
#     (apex_displacement, column 2), and rows: how many
function summary_value(line, key,    v, out) {
    if (index(line, "\"" key "\": ") == 0) return
    v = substr(line, index(line, "\"" key "\": ") + length(key) + 4)
    if (substr(v, 1, 1) == "\"") {   # a string: to the closing quote
        v = substr(v, 2); out = ""
        while (length(v) > 0 && substr(v, 1, 1) != "\"") {
            if (substr(v, 1, 1) == "\\") v = substr(v, 2)
            out = out substr(v, 1, 1); v = substr(v, 2)
        }
        print key, out
    } else {
        sub(/[,}].*$/, "", v); print key, v
    }
}
mode == "l2" {
    if (FNR == 1) { file++; next }
    if (file == 1) a[FNR] = $2
    else if (file == 2) b[FNR] = $2
    else { r[FNR] = $2; if (FNR in a && FNR in b) { num += (a[FNR] - b[FNR])^2; den += $2^2; n++ } }
    next
}
FILENAME ~ /summary\.json$/ {
    if ($0 ~ /^  "(status|error|peak_displacement|peak_time|max_clamp_slip|final_projectile_velocity)": /) {
        key = $0; sub(/^  "/, "", key); sub(/".*$/, "", key); summary_value($0, key)
    }
    next
}
FILENAME ~ /profiles\.csv$/ {
    if (FNR == 1) next
    split($0, f, ",")
    t = f[1]   # the time as written: the same text on every row of one profile
    if (!(t in seen)) { seen[t] = 1; times[++nt] = t }
    i = (f[2] == "warp") ? nw[t]++ : nf[t]++
    if (f[2] == "warp") warp[t, i] = f[4]; else weft[t, i] = f[4]
    next
}
END {
    if (mode == "l2") {
        if (n > 0 && den > 0) printf "apex_l2 %.10g\nrows %d\n", sqrt(num / den), n
        else printf "rows %d\n", n
        exit
    }
    best = ""
    for (k = 1; k <= nt; k++)
        if (best == "" || (times[k] - profile_time)^2 < (best - profile_time)^2) best = times[k]
    if (best == "") exit
    m = (nw[best] < nf[best]) ? nw[best] : nf[best]
    diff = 0
    for (i = 0; i < m; i++) {
        d = warp[best, i] - weft[best, i]; if (d < 0) d = -d
        if (d > diff) diff = d
    }
    apex = warp[best, 0]
    printf "profile_time %.10g\n", best
    if (apex != 0) printf "warp_weft_difference %.10g\n", diff / apex
}
