# crater.gp — the crater in the backing block at the run's end: the top face's
# indentation (m, downward) along x through the impact point (crater.csv: x, depth),
# with the back-face signature (the settled crater's depth, its mean over the last window; or the deepest point at the end) and the dynamic peak marked.
# gnuplot -e "data='crater.csv'; out='crater.png'; bfs=0.02; peak=0.025" freefem_scripts/plots/crater.gp
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1000,500 font ',11'
set output out
set title sprintf('Crater in the backing at the end: back-face signature %.4g m (dynamic peak %.4g m)', bfs, peak) font ',10'
set xlabel 'x (m)'
set format x '%h'
set ylabel 'top face z displacement (m, down = into the block)'
set grid
set autoscale xfix
set yrange [*:*] reverse
set key right bottom box opaque
plot data using (column('x')):(column('depth')) with linespoints pt 7 ps 0.6 lw 2 lc rgb '#8c564b' title 'top face at the end', \
     bfs with lines dt 2 lw 1.5 lc rgb '#1f77b4' title 'back-face signature', \
     peak with lines dt 3 lw 1.5 lc rgb '#d62728' title 'dynamic peak'
