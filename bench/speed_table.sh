#!/bin/sh
# The speed table of issue 12 from make bench's raw figures: one row per
# figure, each with its measured value, what it is compared against, the ratio,
# the target and met/missed. Writes OUT/speed_table.json (one key per row) and
# OUT/speed.md (the markdown table docs/speed.md's speed table is copied from).
# Knows nothing of how the figures were measured (bench/run.sh does that): it
# only reads the files below, so tests/sh/speed_table.sh can feed it canned ones.
#
# usage: sh bench/speed_table.sh IN OUT
#   IN/kernel.jsonl  bench/kernel_speed lines, each with "size_factor" added by
#                    bench/run.sh (0.21: ~50k triangles, 0.067: ~493k)
#   IN/scenes.txt    "key value..." lines (any may be missing: the row is then
#                    "not measured"):
#     scene_wall_seconds S     the paper's scene at its defaults, start to plots
#     scene_cpu_seconds S      the same, user + system CPU of every process
#     scene_summary TEXT       its "peak displacement ... %" summary
#     strip_wall_seconds S     the strip scene at its defaults, start to plots
#     strip_cpu_seconds S      the same, user + system CPU
#     amplitudes_dynamic_summary FILE   summary.json of a run with -amplitudes dynamic
#     amplitudes_static_summary FILE    the same run with -amplitudes static
#                    (FILE relative to IN unless absolute)
#
# The row keys (and what "ratio" is in each):
#   king_tri3_50k_1thread       ns per element-step of the King tri3 step, 1 thread, ~50k
#                               elements; against the bare linear CST beside it; ratio
#                               = King / CST; target <= 2.5
#   threads_2_vs_1_50k          ns per element-step with 2 threads; against 1 thread;
#                               ratio = speed-up (1 thread / 2 threads); target >= 1.8
#   tri3_493k_vs_50k            ns per element-step at ~493k elements, 1 thread;
#                               against ~50k; ratio = 493k / 50k; target <= 1.2
#   quad4_vs_tri3_50k           ns per element-step of quad4 at the ~50k size factor,
#                               1 thread; against tri3; ratio = quad4 / tri3; target <= 2
#   amplitudes_static_vs_dynamic   µs per step of the scene with -amplitudes static;
#                               against dynamic; ratio = static / dynamic; target <= 3
#   scene_make_run              the paper's scene start to plots, s; target <= 4 s and the
#                               summary numbers unchanged; ratio = value / 4 s
#   strip_scene_default         the strip scene at its quasi-static default, s; target
#                               <= 20 s; ratio = value / 20 s
#   memory_per_element          bytes per element of the model's arrays, tri3 ~50k; target
#                               <= 1024 B; ratio = value / 1024 B (peak RSS beside it)
# Every row: {"figure", "unit", "value", "against", "ratio", "target", "met"}; "met" is
# true, false or null (not measured); "target" reads e.g. "<= 2.5x" or "<= 4 s".
set -u
in=${1:?usage: speed_table.sh IN OUT}
out=${2:?usage: speed_table.sh IN OUT}
kernel="$in/kernel.jsonl"; [ -f "$kernel" ] || kernel=/dev/null   # (missing: those rows not measured)
scenes="$in/scenes.txt"; [ -f "$scenes" ] || scenes=/dev/null
summary_of() { # key: the summary.json named by scenes.txt, or /dev/null
    f=$(sed -n "s/^$1 //p" "$scenes" | head -1)
    [ -z "$f" ] && { echo /dev/null; return; }
    case $f in /*) ;; *) f="$in/$f" ;; esac
    [ -f "$f" ] && echo "$f" || echo /dev/null
}
dyn=$(summary_of amplitudes_dynamic_summary); sta=$(summary_of amplitudes_static_summary)
awk -v json="$out/speed_table.json.tmp" -v md="$out/speed.md.tmp" \
    -v kernel="$kernel" -v scenes="$scenes" -v dyn="$dyn" -v sta="$sta" '
function num(line, key,    s) {   # the number after "key": in a JSON line, "" if none
    s = line
    if (!match(s, "\"" key "\": *-?[0-9.eE+-]+")) return ""
    s = substr(s, RSTART, RLENGTH); sub(/^[^:]*: */, "", s); return s
}
function kernel_row(type, sf, threads,    i) {   # index of the matching kernel line, 0 if none
    for (i = 1; i <= nk; i++)
        if (K[i] ~ "\"element_type\": \"" type "\"" && num(K[i], "size_factor") + 0 == sf + 0 &&
            num(K[i], "threads") + 0 == threads) return i
    return 0
}
function jnum(x) { return x == "" ? "null" : sprintf("%.6g", x) }
function jstr(s) { gsub(/\\/, "\\\\", s); gsub(/"/, "\\\"", s); return "\"" s "\"" }
# one row: key, figure, unit, value, against ("" none), ratio, op, target, target text,
# compared ("ratio" or "value"), extra JSON members ("" none), extra md text
function row(key, figure, unit, value, against, ratio, op, target, ttext, compared, extra, mdextra,
             x, met, m) {
    x = compared == "ratio" ? ratio : value
    if (x == "" || value == "") met = "null"
    else met = (op == "<=" ? x + 0 <= target + 0 : x + 0 >= target + 0) ? "true" : "false"
    if (key == "scene_make_run" && met == "true" && same != "true") met = "false"
    if (nrows++) printf ",\n" > json
    printf "  %s: {\"figure\": %s, \"unit\": %s, \"value\": %s, \"against\": %s, \"ratio\": %s, " \
           "\"target\": %s, \"met\": %s%s}", jstr(key), jstr(figure), jstr(unit), jnum(value),
           jnum(against), ratio == "" ? "null" : sprintf("%.3f", ratio), jstr(ttext), met,
           extra == "" ? "" : ", " extra > json
    m = met == "true" ? "met" : met == "false" ? "**missed**" : "not measured"
    gsub(/<=/, "≤", ttext); gsub(/>=/, "≥", ttext)
    printf "| %s | %s | %s | %s | %s |\n", figure,
           value == "" ? "—" : sprintf("%.4g %s", value, unit) (against == "" ? "" : sprintf(" vs %.4g", against)) mdextra,
           ratio == "" ? "—" : sprintf("%.2fx", ratio) (compared == "value" ? " the limit" : ""), ttext, m > md
}
function div(a, b) { return (a == "" || b == "" || b + 0 == 0) ? "" : a / b }
BEGIN {
    expected = "peak displacement 31.8259 mm at 1.83001 ms, largest energy error 6.26259e-05 %"
    while ((getline l < kernel) > 0) if (l ~ /^{/) K[++nk] = l
    while ((getline l < scenes) > 0) {
        k = l; sub(/ .*/, "", k); v = l; sub(/^[^ ]* ?/, "", v); if (!(k in S)) S[k] = v
    }
    while ((getline l < dyn) > 0) { if (num(l, "wall_seconds") != "") dw = num(l, "wall_seconds")
                                    if (num(l, "steps") != "") ds = num(l, "steps") }
    while ((getline l < sta) > 0) { if (num(l, "wall_seconds") != "") sw = num(l, "wall_seconds")
                                    if (num(l, "steps") != "") ss = num(l, "steps") }
    print "{" > json
    print "| figure | measured | ratio | target | met |" > md
    print "|---|---|---|---|---|" > md

    t1 = kernel_row("tri3", 0.21, 1); t2 = kernel_row("tri3", 0.21, 2)
    tb = kernel_row("tri3", 0.067, 1); q1 = kernel_row("quad4", 0.21, 1)
    k1 = t1 ? num(K[t1], "ns_per_element_step") : ""; cst = t1 ? num(K[t1], "linear_membrane_ns") : ""
    k2 = t2 ? num(K[t2], "ns_per_element_step") : ""; kb = tb ? num(K[tb], "ns_per_element_step") : ""
    kq = q1 ? num(K[q1], "ns_per_element_step") : ""
    n1 = t1 ? num(K[t1], "elements") : ""; nb = tb ? num(K[tb], "elements") : ""
    nq = q1 ? num(K[q1], "elements") : ""
    row("king_tri3_50k_1thread", "King tri3, 1 thread, " (n1 == "" ? "~50k" : n1) " elements, ns per element-step (forces + update + contact), against the bare linear CST beside it",
        "ns", k1, cst, div(k1, cst), "<=", 2.5, "<= 2.5x", "ratio",
        n1 == "" ? "" : "\"elements\": " n1, "")
    row("threads_2_vs_1_50k", "2 threads vs 1, ~50k elements (speed-up)", "ns", k2, k1, div(k1, k2),
        ">=", 1.8, ">= 1.8x", "ratio", "", "")
    row("tri3_493k_vs_50k", (nb == "" ? "~493k" : nb) " elements vs ~50k, per element-step, 1 thread", "ns", kb, k1,
        div(kb, k1), "<=", 1.2, "<= 1.2x", "ratio", nb == "" ? "" : "\"elements\": " nb, "")
    row("quad4_vs_tri3_50k", "quad4 vs tri3, per element-step, 1 thread, the ~50k size (" (nq == "" ? "?" : nq) " quads)",
        "ns", kq, k1, div(kq, k1), "<=", 2, "<= 2x", "ratio", nq == "" ? "" : "\"elements\": " nq, "")
    dstep = (dw != "" && ds > 0) ? 1e6 * dw / ds : ""; sstep = (sw != "" && ss > 0) ? 1e6 * sw / ss : ""
    row("amplitudes_static_vs_dynamic", "`-amplitudes static` vs dynamic, per step (the paper'\''s scene)", "µs per step",
        sstep, dstep, div(sstep, dstep), "<=", 3, "<= 3x", "ratio",
        ds == "" && ss == "" ? "" : "\"steps_dynamic\": " jnum(ds) ", \"steps_static\": " jnum(ss), "")
    sum = ("scene_summary" in S) ? S["scene_summary"] : ""
    same = sum == expected ? "true" : "false"
    sv = ("scene_wall_seconds" in S) ? S["scene_wall_seconds"] : ""
    sc = ("scene_cpu_seconds" in S) ? S["scene_cpu_seconds"] : ""
    row("scene_make_run", "the paper'\''s scene, `make run`, start to plots, same summary numbers", "s",
        sv, "", div(sv, 4), "<=", 4, "<= 4 s, same summary", "value",
        "\"cpu_seconds\": " jnum(sc) ", \"summary\": " jstr(sum) ", \"expected_summary\": " jstr(expected) \
        ", \"summary_same\": " (sum == "" ? "null" : same),
        (sc == "" ? "" : sprintf(" (%.3g s CPU)", sc)) (sum == "" ? "" : same == "true" ? ", summary same" : ", **summary differs**: " sum))
    tv = ("strip_wall_seconds" in S) ? S["strip_wall_seconds"] : ""
    tc = ("strip_cpu_seconds" in S) ? S["strip_cpu_seconds"] : ""
    row("strip_scene_default", "the strip scene (640 quads, §2.3) at its quasi-static default, start to plots", "s",
        tv, "", div(tv, 20), "<=", 20, "<= 20 s", "value", "\"cpu_seconds\": " jnum(tc),
        tc == "" ? "" : sprintf(" (%.3g s CPU)", tc))
    mb = t1 ? num(K[t1], "model_bytes_per_element") : ""; rss = t1 ? num(K[t1], "peak_rss_bytes_per_element") : ""
    row("memory_per_element", "memory per element (the model'\''s arrays; tri3, ~50k)", "B", mb, "", div(mb, 1024),
        "<=", 1024, "<= 1 KB", "value", "\"peak_rss_bytes_per_element\": " jnum(rss),
        rss == "" ? "" : sprintf(" (peak RSS %.4g B)", rss))
    print "\n}" > json
}' || exit 1
mv "$out/speed_table.json.tmp" "$out/speed_table.json" && mv "$out/speed.md.tmp" "$out/speed.md"
