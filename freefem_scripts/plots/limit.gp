# limit.gp — a ballistic-limit sweep (freefem_scripts/ballistic_limit.edp): the residual
# speed of each run against its striking speed (perforated: filled circles; stopped:
# open squares at 0), the fitted Lambert-Jonas law V_r = a (V_s^p - V_bl^p)^(1/p), the
# V50 of the bracket (mid-point +- half the gap, shaded) and V_bl (dashed). The words
# are the scene's, as its terminal prints them (one rounding): the fit, the bracket's
# V50 and up to 3 warnings (V_bl at its bound, a > 1, a or p at its bound) in red.
#   gnuplot -e "datafile='limit.csv'; out='limit.png'; vbl=150; a=0.8; p=2; v50b=151; v50b_half=3;
#               fit_text='V_bl 150 +- 1 m/s, a 0.8 +- 0.01, p 2 +- 0.1'; bracket_text='151 +- 3 m/s (bracket)';
#               warnings=0; warning1=''; warning2=''; warning3=''" freefem_scripts/plots/limit.gp
# datafile: limit.csv (striking_velocity, residual_velocity, perforated 1/0/empty, ...).
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1000,650 font ',11'
set output out
set title sprintf("Ballistic limit: %s\nV50 %s", fit_text, bracket_text) noenhanced
if (warnings > 0) {
    set bmargin 4 + warnings
    set label 11 'warning: ' . warning1 at screen 0.01, screen 0.01 + 0.03 * (warnings - 1) left front font ',9' tc rgb '#d62728' noenhanced
}
if (warnings > 1) { set label 12 'warning: ' . warning2 at screen 0.01, screen 0.01 + 0.03 * (warnings - 2) left front font ',9' tc rgb '#d62728' noenhanced }
if (warnings > 2) { set label 13 'warning: ' . warning3 at screen 0.01, screen 0.01 left front font ',9' tc rgb '#d62728' noenhanced }
set xlabel 'striking speed V_s (m/s)'
set ylabel 'residual speed V_r (m/s)'
set grid
set key left top box opaque
stats datafile using 1 nooutput
xmax = STATS_max * 1.05
xmin = STATS_min * 0.9
set xrange [xmin:xmax]
set yrange [0:*]
set offsets 0, 0, graph 0.05, 0
law(x) = x > vbl ? a * (x**p - vbl**p)**(1.0 / p) : 0
set samples 400
if (v50b == v50b) {
    set object 1 rect from v50b - v50b_half, graph 0 to v50b + v50b_half, graph 1 fc rgb '#dddddd' fs solid 0.6 noborder behind
}
set arrow 1 from vbl, graph 0 to vbl, graph 1 nohead dt 2 lw 1.5 lc rgb 'black'
plot law(x) with lines lw 2.5 lc rgb '#1f77b4' title 'Lambert-Jonas fit', \
     datafile using 1:(column(3) == 1 ? column(2) : NaN) with points pt 7 ps 1.6 lc rgb '#d62728' title 'perforated', \
     datafile using 1:(column(3) == 0 ? 0 : NaN) with points pt 4 ps 1.6 lw 2 lc rgb '#2ca02c' title 'stopped', \
     NaN with boxes fc rgb '#dddddd' fs solid 0.6 title 'V50 from the bracket'
