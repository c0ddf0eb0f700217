# explorer_pullout.gp — the unit-cell explorer's pull-out path: one cell whose warp is
# pulled while the weft is held at a yarn tension (the crossing yarns' pretension), with
# yarn slip at the crossovers (docs/model.md §24): the warp sticks, its tension rising
# with crimp interchange, then slides through the crossovers at the slip tension
# n_c mu_yy F_I; the slip grows and the friction's work is dissipated. Called by
# unit_cell_explorer.edp as
#   gnuplot -e "csv='pullout.csv'; heading='...'; out='pullout.png'" explorer_pullout.gp
# csv      the path's CSV (columns by name: pull_strain, T1, T2, F_I, slip_1, slip_2,
#          dissipated_slip; SI)
# heading  the title: the path, cell, material
# slip     1: the material slips (slip_1, slip_2 columns); 0: those panels say it does not
# Three panels against the pull strain (-): the yarn tensions and the crossover force (N),
# the slip strains (-), the energy dissipated by slip (J/m^2).
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1500, 520 font ',11'
set output out
set multiplot layout 1, 3 title heading noenhanced
set grid
set format x '%h'; set format y '%h'
set key left top box opaque
set xlabel "pull strain of the warp beyond its preload (-)"
set title "yarn tensions and crossover force"
set ylabel "force (N)"
plot csv using "pull_strain":"T1" w l lw 2.5 lc 1 title "T_1, the pulled warp", \
     csv using "pull_strain":"T2" w l lw 2.5 lc 2 title "T_2, the held weft", \
     csv using "pull_strain":"F_I" w l lw 2.5 dt 2 lc 3 title "F_I, crossover force"
set title "slip through the crossovers"
set ylabel "slip strain s_k (-)"
if (slip) {
    plot csv using "pull_strain":"slip_1" w l lw 2.5 lc 1 title "s_1, warp", \
         csv using "pull_strain":"slip_2" w l lw 2.5 lc 2 title "s_2, weft"
} else {
    set label 1 "no yarn slip in this material\n(yarn\\_friction = 0: -set yarn\\_friction=0.2)" at graph 0.5, 0.5 center
    plot csv using "pull_strain":(0) w l lw 2.5 lc 1 title "s_1 = s_2 = 0"
    unset label 1
}
set title "energy dissipated by slip"
set ylabel "dissipated (J/m^2)"
plot csv using "pull_strain":"dissipated_slip" w l lw 2.5 lc 1 title "friction's work at the crossovers"
unset multiplot
