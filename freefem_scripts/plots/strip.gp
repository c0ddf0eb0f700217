# strip.gp — load per width against nominal strain of the warp and weft strips
# (cf. the paper's Fig. 5): the explicit strip as coloured lines, the static
# one-point solution as black open markers on top (every 10th sample).
# gnuplot -e "warp='strip_warp.csv'; weft='strip_weft.csv'; out='strip.png'; material='x.txt'" \
#         freefem_scripts/plots/strip.gp
# warp, weft: the strip scene's CSVs ('' for a family not pulled).
# The values are the CSVs' as they are (SI): the axes say their units.
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1000,650 font ',11'
set output out
set title sprintf("Strip tension, %s (cf. paper Fig. 5)", material) noenhanced
set xlabel 'nominal strain (-)'
set ylabel 'load per width (N/m)'
set grid
set format x '%h'; set format y '%h'
set autoscale yfix
set offsets 0, 0, graph 0.05, graph 0.05
set key left top box opaque
strain = '(column("strain"))'
files = warp.' '.weft
names = (warp eq '' ? '' : 'warp ').(weft eq '' ? '' : 'weft')
file(i) = word(files, i)
plot for [i = 1:words(files)] file(i) using @strain:(column('load_per_width')) \
        with lines lw 3 lc i title word(names, i).', explicit strip', \
     for [i = 1:words(files)] file(i) using @strain:(column('load_static')) every 10 \
        with points pt (i == 1 ? 6 : 4) ps 1.8 lw 2 lc rgb 'black' title word(names, i).', static point (GSL)'
