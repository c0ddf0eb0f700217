# mil662.gp — the MIL-STD-662F sequence of ballistic_limit.edp -method mil662: each
# shot's striking speed against its number in the firing order (complete
# penetrations: filled red circles; partial: open green squares; neither, undecided
# or failed: grey crosses), the six shots of the V50 ringed, the V50 (dashed, when
# the rule is met). The title and the V50's label are the scene's own words (one rounding).
#   gnuplot -e "datafile='mil662.csv'; out='mil662.png'; v50=16.4; v50_text='16.4'; title_text='MIL-STD-662F: V50 ...'"
#       freefem_scripts/plots/mil662.gp
# datafile: mil662.csv (shot, striking_velocity, complete 1/0/empty, status, plies_holed, in_six, ...).
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1000,650 font ',11'
set output out
set title title_text noenhanced
set xlabel 'shot, in firing order (-)'
set ylabel 'striking speed (m/s)'
set grid
set key below horizontal box
set bmargin 7
stats datafile using 1 nooutput
set xrange [0.5:STATS_max + 0.5]
set xtics 1
set offsets 0, 0, graph 0.08, graph 0.08
if (v50 == v50) {
    set arrow 1 from graph 0, first v50 to graph 1, first v50 nohead dt 2 lw 1.5 lc rgb 'black'
    set label 1 'V50 ' . v50_text . ' m/s' at graph 0.01, first v50 offset 0, 0.6 left front
}
plot datafile using 1:(column(3) == 1 ? column(2) : NaN) with points pt 7 ps 1.8 lc rgb '#d62728' title 'complete', \
     datafile using 1:(strcol(3) eq '0' ? column(2) : NaN) with points pt 4 ps 1.8 lw 2 lc rgb '#2ca02c' title 'partial', \
     datafile using 1:(strcol(3) eq '' ? column(2) : NaN) with points pt 2 ps 1.8 lw 2 lc rgb '#7f7f7f' title 'neither (undecided, failed)', \
     datafile using 1:(column(6) == 1 ? column(2) : NaN) with points pt 6 ps 3.2 lw 1.5 lc rgb 'black' title 'the six of the V50', \
     datafile using 1:2 with lines lw 1 lc rgb '#aaaaaa' notitle
