# limit.gp — a ballistic-limit sweep (freefem_scripts/ballistic_limit.edp): the residual
# speed of each run against its striking speed (perforated: filled circles; stopped:
# open squares at 0), the fitted Lambert-Jonas law V_r = a (V_s^p - V_bl^p)^(1/p), the
# V50 of the bracket (mid-point +- half the gap, shaded) and V_bl (dashed).
#   gnuplot -e "datafile='limit.csv'; out='limit.png'; vbl=150; a=0.8; p=2; vbl_se=1;
#               v50b=151; v50b_half=3" freefem_scripts/plots/limit.gp
# datafile: limit.csv (striking_velocity, residual_velocity, perforated 1/0/empty, ...).
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1000,650 font ',11'
set output out
set title sprintf("Ballistic limit: V_{bl} = %.4g +- %.2g m/s, a = %.3g, p = %.3g; V50 (bracket) = %.4g +- %.2g m/s", \
                  vbl, vbl_se, a, p, v50b, v50b_half)
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
