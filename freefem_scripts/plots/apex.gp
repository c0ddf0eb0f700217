# apex.gp — the fabric's transverse displacement at the point of impact and the
# projectile's nose tip (cf. the paper's Fig. 10), with their difference below
# (in contact the two lines coincide to a fraction of a nanometre).
# gnuplot -e "data='history.csv'; out='apex.png'" freefem_scripts/plots/apex.gp
# data: the ballistic scene's history.csv (columns addressed by name).
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1000,750 font ',11'
set output out
t_ms(c) = column('time') * 1e3
apex_mm = '(column("apex_displacement") * 1e3)'
nose_mm = '(column("projectile_displacement") * 1e3)'
set multiplot title 'Transverse displacement at the point of impact (cf. paper Fig. 10)'
set lmargin 12; set rmargin 4
set grid
set autoscale xfix
set origin 0, 0.34; set size 1, 0.60
set ylabel 'displacement (mm)'
set format x ''
set offsets 0, 0, graph 0.15, 0
set key left top box opaque
plot data using (t_ms(0)):(@apex_mm) with lines lw 3 lc rgb '#1f77b4' title 'fabric apex', \
     '' using (t_ms(0)):(@nose_mm) every 8 with points pt 7 ps 0.6 lc rgb '#d62728' \
        title 'projectile nose tip (every 8th frame)'
set origin 0, 0.02; set size 1, 0.33
set offsets 0, 0, graph 0.45, 0
set format x '%g'
set xlabel 'time (ms)'
set ylabel 'apex - nose (nm)'
set key left top box opaque
plot data using (t_ms(0)):((@apex_mm - @nose_mm) * 1e6) with lines lw 2 lc rgb '#2ca02c' \
        title 'fabric apex minus nose tip (steps: the CSV keeps 10 digits)'
unset multiplot
