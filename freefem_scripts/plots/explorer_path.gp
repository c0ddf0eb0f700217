# explorer_path.gp — the unit-cell explorer's six panels for one load path,
# drawn from the path's CSV by column name (any cell: its own diagnostics and
# mechanisms). Called by unit_cell_explorer.edp as
#   gnuplot -e "csv='P.csv'; out='P.png'; path='warp'; cols='...'; units='...'; heading='...'; dynamic=0; lock=NaN" explorer_path.gp
# csv      the path's CSV (first column the load, then time and the cell's columns)
# cols     the CSV's column names, space-separated, in its order
# units    the unit of every CSV column, space-separated, in the CSV's order
# path     warp | weft | equibiaxial | equalforce | shear (sets the x axis)
# heading  the title: path, cell, material, mode
# dynamic  1: dynamic amplitudes (the static balance is drawn dashed beside)
# lock     shear only: the locking angle (rad; NaN: no locking within the path),
#          a labelled vertical line in every panel
# Every value is drawn as the CSV holds it (SI, docs/csv_columns.md) and every
# axis says the unit of the columns it shows, taken from `units`: a number read
# off a picture is found in the CSV as it is (tests/sh/picture_units.sh).
set datafile separator ','
set datafile columnheaders
if (!exists("lock")) lock = NaN
# cols: the CSV's column names, space-separated (given by the scene: no shell)
has(name) = strstrt(" " . cols . " ", " " . name . " ") > 0
# the unit of a column, from `units` (the CSV's own, word by word)
col_index(name) = (s = strstrt(" " . cols . " ", " " . name . " "), s > 0 ? words((" " . cols . " ")[1:s]) + 1 : 0)
unit(name) = col_index(name) > 0 ? word(units, col_index(name)) : "?"

# the x axis: the path's load, the CSV's first column as it is
xlab = (path eq "equalforce" ? "yarn tension T, both families" : \
        path eq "shear" ? "shear angle γ" : "nominal strain ε") . " (" . word(units, 1) . ")"
x(dummy) = column(1)

# the cell's forces besides the yarn tensions, and its mechanisms
forces = ""; mechs = ""
do for [i = 3:words(cols)] {
    n = word(cols, i)
    if (word(units, i) eq "N" && n ne "T1" && n ne "T2") { forces = forces . " " . n }
    if (n[1:2] eq "E_") { mechs = mechs . " " . n }
}
stack(i) = sum [j = 1:i] column(word(mechs, j))
sub(n) = (p = strstrt(n, "_"), p > 0 ? n[1:p - 1] . "_{" . n[p + 1:] . "}" : n)   # F_L1 → F_{L1}
# an empty panel that says why
nothing(text) = sprintf("set label 1 '%s' at graph 0.5, 0.5 center; unset tics; unset xlabel; " \
    . "plot [0:1][0:1] -1 notitle; unset label 1; set tics; set xlabel xlab", text)

set terminal pngcairo size 1500,950 font ',10'
set output out
set multiplot layout 2,3 title heading noenhanced
set grid
set key below horizontal
set format x '%h'; set format y '%h'; set format y2 '%h'   # (the default's precision repeats small tics)
set xlabel xlab
# the locking angle: a dotted vertical line in every panel, labelled along it
if (path eq "shear" && lock == lock) {
    set arrow 9 from lock, graph 0 to lock, graph 1 nohead dt 3 lw 1.5 lc rgb "black" front
    set label 9 sprintf("locking: γ_L = %.4g %s", lock, word(units, 1)) at lock, graph 0.5 \
        center rotate by 90 offset -0.8, 0 front font ",9"
}

set title "membrane stress resultants"; set ylabel "P (" . unit("P11") . ")"
plot for [c in "P11 P22 P12"] csv using (x(0)):(column(c)) w l lw 2 title sub("P_" . c[2:])

set title "crimp amplitude changes (A_k = A_k^0 + ΔA_k)"; set ylabel "ΔA (" . unit("dA1") . ")"
if (has("dA1")) {
    plot csv using (x(0)):(column("dA1")) w l lw 2 lc 1 title "ΔA_1 warp", \
         '' using (x(0)):(column("dA2")) w l lw 2 lc 2 title "ΔA_2 weft", \
         for [k = 1:2] '' using (x(0)):(dynamic ? column(sprintf("dA%d_static", k)) : NaN) \
             w l dt 2 lc k title (dynamic ? sprintf("ΔA_%d static balance", k) : "")
} else { eval nothing("this cell has no crimp amplitudes") }

set title "yarn tensions"; set ylabel "T (" . unit("T1") . ")"; set yrange [*<0:0<*]   # from 0: a constant T is no zoom on round-off
plot csv using (x(0)):"T1" w l lw 2 lc 1 title "T_1 warp", '' using (x(0)):"T2" w l lw 2 lc 2 title "T_2 weft"
set autoscale y

set title "the cell's other forces (crossover, spars)"; set ylabel "force (N)"
if (words(forces) > 0) {
    plot for [c in forces] csv using (x(0)):c w l lw 2 title sub(c)
} else { eval nothing("this cell reports no other forces") }

set title "stored energy per mechanism (stacked)"; set ylabel "W (" . unit("W") . ")"
set style fill solid 0.6 noborder
plot for [i = 1:words(mechs)] csv using (x(0)):(i > 1 ? stack(i - 1) : 0):(stack(i)) \
         w filledcurves title word(mechs, i)[3:] noenhanced, \
     '' using (x(0)):"W" w l lw 1 lc rgb "black" dt 2 title "W"

if (path eq "shear") {
    set title "shear angle γ, its flow part γ^f" . (has("M_s") ? " and the shear moment M_s" : "")
    set ylabel "angle (" . unit("gamma") . ")"
    angles = "plot csv using (x(0)):(column('gamma')) w l lw 2 lc 3 title 'γ', " \
           . "'' using (x(0)):(column('gamma_f')) w l dt 2 lw 2 lc 4 title 'γ^f (flow)'"
    if (has("M_s")) {
        set y2label "M_s (" . unit("M_s") . ")"; set y2tics; set ytics nomirror
        eval angles . ", '' using (x(0)):(column('M_s')) axes x1y2 w l lw 2 lc 7 title 'M_s'"
    } else { eval angles }
} else {
    set title "yarn-direction stretches"; set ylabel "λ - 1 (" . unit("lambda1") . ")"
    plot csv using (x(0)):(column("lambda1") - 1) w l lw 2 lc 1 title "λ_1 - 1 warp", \
         '' using (x(0)):(column("lambda2") - 1) w l lw 2 lc 2 title "λ_2 - 1 weft"
}
unset multiplot
