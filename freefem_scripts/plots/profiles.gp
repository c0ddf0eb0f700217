# profiles.gp — transverse displacement along the warp (x) and weft (y) lines
# through the point of impact at the profile times (cf. the paper's Fig. 9).
# gnuplot -e "data='profiles.csv'; out='profiles.png'; times='0.0004 0.0009'; half=5e-6" \
#         freefem_scripts/plots/profiles.gp
# data: rows time,direction,position,displacement; times: the profile times
# (s) present; half: half the history interval (s), to match the times.
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1000,650 font ',11'
set output out
set title 'Transverse displacement through the point of impact (cf. paper Fig. 9)'
set xlabel 'distance from the point of impact (mm)'
set ylabel 'displacement (mm)'
set grid
set key right top box opaque title 'solid: warp (x), dashed: weft (y)'
at(t, d) = abs(column('time') - t) < half && strcol('direction') eq d
mm(c) = column(c) * 1e3
set xrange [0:*]
plot for [i = 1:words(times)] data using (at(word(times, i) + 0, 'warp') ? mm('position') : NaN):(mm('displacement')) \
        with lines lw 2.5 lc i title sprintf('%.1f ms', word(times, i) * 1e3), \
     for [i = 1:words(times)] '' using (at(word(times, i) + 0, 'weft') ? mm('position') : NaN):(mm('displacement')) \
        with lines lw 2.5 dt 2 lc i notitle
