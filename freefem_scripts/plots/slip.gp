# slip.gp — each yarn family's slip strain through the crossovers over the
# quarter model (or the whole specimen) at one time, seen from above: where the
# yarns slide (the continuum's window under the nose, pull-out at the clamp
# edge; docs/model.md §24). Colour slip_k on a log scale from 1e-5 (below it:
# the lowest colour), both panels alike; a slip <= 0 (a family shortened
# through the crossovers, or none) is not drawn (white); the clamp edge
# (r = R) drawn, the clamped fabric grey.
# gnuplot -e "data='slip_2.csv'; out='slip_2.png'; time_s=0.0013; R=0.127" freefem_scripts/plots/slip.gp
# data: rows x,y,slip_1,slip_2 (m, m, -, -) on a regular grid; time_s (s); R (m).
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1300,620 font ',11'
set output out
stats data using (column('x')) nooutput name 'X'
stats data using (column('slip_1') > column('slip_2') ? column('slip_1') : column('slip_2')) nooutput name 'S'
stats data using (column('slip_1') < column('slip_2') ? column('slip_1') : column('slip_2')) nooutput name 'L'
whole = X_min < 0
floor_ = 1e-5
top = S_max > 10 * floor_ ? S_max : 10 * floor_
set multiplot layout 1,2 title sprintf('Yarn slip through the crossovers at t = %.3g s (%s); largest slip %.3g, smallest %.3g (<= 0: white)', time_s, whole ? 'whole specimen' : 'quarter model', S_max, L_min)
set xlabel 'x, along the warp (m)'
set ylabel 'y, along the weft (m)'
set cblabel 'slip strain s_k (-)'
set format x '%h'; set format y '%h'; set format cb '%.0e'
set size ratio -1
set xrange [X_min:X_max]; set yrange [X_min:X_max]
set logscale cb; set cbrange [floor_:top]
set palette cubehelix start 0.5 cycles -1.2 saturation 1.2 negative
set object 1 rectangle from graph 0, graph 0 to graph 1, graph 1 behind fillcolor rgb '#d9d9d9' fillstyle solid noborder
set object 2 circle at 0, 0 size R arc [0:(whole ? 360 : 90)] behind fillcolor rgb 'white' fillstyle solid noborder
set parametric; set trange [0:(whole ? 2 * pi : pi / 2)]; set samples 200
set key at graph 0.98, graph 0.98 box opaque
inside(x, y) = x**2 + y**2 <= R**2
set title 'warp (family 1): slip\_1'
plot data using (column('x')):(column('y')):(inside(column('x'), column('y')) ? column('slip_1') : NaN) with image notitle, \
     R * cos(t), R * sin(t) with lines lw 2.5 lc rgb 'black' title sprintf('clamp edge, r = %g m', R)
set title 'weft (family 2): slip\_2'
plot data using (column('x')):(column('y')):(inside(column('x'), column('y')) ? column('slip_2') : NaN) with image notitle, \
     R * cos(t), R * sin(t) with lines lw 2.5 lc rgb 'black' title sprintf('clamp edge, r = %g m', R)
unset multiplot
