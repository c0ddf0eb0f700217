# tornado.gp — a tornado chart of a sensitivity study (freefem_scripts/sensitivity.edp
# draws one per observable). Data: tab-separated rows "position  input  change at
# the low end  change at the high end" (NaN: the run failed), sorted so the largest
# swing is the last row (drawn on top).
#   gnuplot -e "datafile='x.dat'; outfile='x.png'; charttitle='...'; xlabeltext='...'; notetext='...'; rows=N; flat=0" tornado.gp
# (flat=1: every change is zero; the x range is then fixed at [-1:1])
set terminal pngcairo size 1150,(rows * 26 + 170 > 430 ? rows * 26 + 170 : 430) font ',10'
set output outfile
set datafile separator "\t"
set datafile missing "NaN"
set title charttitle noenhanced
set xlabel (notetext eq '' ? xlabeltext : xlabeltext . "\n" . notetext) noenhanced
set ylabel ''
set yrange [0.3:rows + 0.7]
set ytics nomirror noenhanced
set grid xtics
set xzeroaxis lt -1 lw 1
set key outside bottom center horizontal
set bmargin 6
set style fill transparent solid 0.65 border -1
set offsets graph 0.05, graph 0.05, 0, 0
if (flat) set xrange [-1:1]
# boxxyerror: x y xlow xhigh ylow yhigh; a bar from 0 to the change
plot datafile using ($3 / 2):1:($3 < 0 ? $3 : 0):($3 < 0 ? 0 : $3):($1 - 0.36):($1 + 0.36):ytic(2) \
        with boxxyerror lc rgb '#3b6fb6' title 'input at the low end of its range', \
     '' using ($4 / 2):1:($4 < 0 ? $4 : 0):($4 < 0 ? 0 : $4):($1 - 0.36):($1 + 0.36) \
        with boxxyerror lc rgb '#d0452f' title 'input at the high end'
unset output
