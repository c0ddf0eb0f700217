# profiles.gp — transverse displacement along the warp (x) and weft (y) lines
# through the point of impact at the profile times (cf. the paper's Fig. 9).
# gnuplot -e "data='profiles.csv'; out='profiles.png'; times='0.0004 0.0009'; half=5e-6" \
#         freefem_scripts/plots/profiles.gp
# data: rows time,direction,position,displacement; times: the profile times
# (s) present; half: half the history interval (s), to match the times.
# The values are the CSV's as they are (SI: m, the times in s).
set datafile separator ','
# a number from its text: gnuplot reads "2e-05" + 0 as 2 followed by junk (an error), so a
# mantissa without a point gets one
num(s) = (p_ = strstrt(s, "e"), p_ > 0 && strstrt(s, ".") == 0 ? (s[1:p_ - 1] . ".0" . s[p_:]) + 0 : s + 0)
set datafile columnheaders
set terminal pngcairo size 1000,650 font ',11'
set output out
set title 'Transverse displacement through the point of impact (cf. paper Fig. 9)'
set xlabel 'distance from the point of impact (m)'
set ylabel 'displacement (m)'
set grid
set format x '%h'; set format y '%h'
set key right top box opaque title 'solid: warp (x), dashed: weft (y)'
at(t, d) = abs(column('time') - t) < half && strcol('direction') eq d
set xrange [0:*]
plot for [i = 1:words(times)] data using (at(num(word(times, i)), 'warp') ? column('position') : NaN):(column('displacement')) \
        with lines lw 2.5 lc i title sprintf('t = %.3g s', num(word(times, i))), \
     for [i = 1:words(times)] '' using (at(num(word(times, i)), 'weft') ? column('position') : NaN):(column('displacement')) \
        with lines lw 2.5 dt 2 lc i notitle
