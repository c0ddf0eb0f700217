# apex.gp — the fabric's transverse displacement at the point of impact and the
# projectile's nose tip (cf. the paper's Fig. 10), with their difference below
# (in contact the two lines coincide to a fraction of a nanometre).
# gnuplot -e "data='history.csv'; out='apex.png'" freefem_scripts/plots/apex.gp
# data: the ballistic scene's history.csv (columns addressed by name); the values
# as it holds them (SI: s, m).
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1000,750 font ',11'
set output out
t_s(c) = column('time')
apex = '(column("apex_displacement"))'
nose = '(column("projectile_displacement"))'
set multiplot title 'Transverse displacement at the point of impact (cf. paper Fig. 10)'
set lmargin 12; set rmargin 4
set grid
set autoscale xfix
set origin 0, 0.34; set size 1, 0.60
set ylabel 'displacement (m)'
set format y '%h'
set format x ''
set offsets 0, 0, graph 0.15, 0
set key left top box opaque
plot data using (t_s(0)):(@apex) with lines lw 3 lc rgb '#1f77b4' title 'fabric apex', \
     '' using (t_s(0)):(@nose) every 8 with points pt 7 ps 0.6 lc rgb '#d62728' \
        title 'projectile nose tip (every 8th frame)'
set origin 0, 0.02; set size 1, 0.33
set offsets 0, 0, graph 0.45, 0
set format x '%h'
set xlabel 'time (s)'
set ylabel 'apex - nose (m)'
set key left top box opaque
plot data using (t_s(0)):(@apex - @nose) with lines lw 2 lc rgb '#2ca02c' \
        title 'fabric apex minus nose tip (steps: the CSV keeps 10 digits)'
unset multiplot
