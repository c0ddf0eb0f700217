# wrinkle.gp — the out-of-plane undulation near the clamp edge (uz less its
# local trend, tools/wrinkle.awk), friction clamp beside fixed clamp, at one
# time: a wrinkle would show as alternating bands across the ring that the
# fixed clamp (no draw-in) does not have (docs/wrinkling.md).
# gnuplot -e "friction='a.csv'; fixed='b.csv'; out='wrinkle.png'; R=0.127; time_s=0.002; speed=60" \
#         freefem_scripts/plots/wrinkle.gp
# friction, fixed: rows x,y,undulation (m); R: the clamp edge (m); time_s (s); speed (m/s).
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1300,620 font ',11'
set output out
set multiplot layout 1,2 title sprintf('Undulation near the clamp edge (u_z less its 8 mm trend) at t = %.3g s, %g m/s, quarter model (cf. paper Fig. 11)', time_s, speed)
set xlabel 'x, along the warp (m)'
set ylabel 'y, along the weft (m)'
set cblabel 'undulation (m)'
set format x '%h'; set format y '%h'; set format cb '%.0e'
set size ratio -1
set xrange [0:R * 1.02]; set yrange [0:R * 1.02]
stats friction using 3 nooutput name 'A'
stats fixed using 3 nooutput name 'B'
top = A_max > -A_min ? A_max : -A_min
top = B_max > top ? B_max : top
top = -B_min > top ? -B_min : top
set cbrange [-top:top]
set palette defined (-1 '#2166ac', 0 '#f7f7f7', 1 '#b2182b')
set parametric; set trange [0:pi / 2]; set samples 200
set key at graph 0.98, graph 0.98 box opaque
set title 'friction clamp (the fabric draws in)'
plot friction using 1:2:3 with points pt 5 ps 0.45 lc palette notitle, \
     R * cos(t), R * sin(t) with lines lw 2 lc rgb 'black' title sprintf('clamp edge, r = %.3g m', R)
set title 'fixed clamp (no draw-in): the baseline'
plot fixed using 1:2:3 with points pt 5 ps 0.45 lc palette notitle, \
     R * cos(t), R * sin(t) with lines lw 2 lc rgb 'black' title sprintf('clamp edge, r = %.3g m', R)
unset multiplot
