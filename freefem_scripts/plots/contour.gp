# contour.gp — transverse displacement of the quarter model (or, for a grid
# reaching x < 0, the whole specimen struck off the centre) at one time, seen
# from above (cf. the paper's Fig. 11): colour u_z, axes x, y, all in m as the
# CSV holds them; the clamp edge (the opening, r = R) drawn; the clamped fabric
# outside it is grey.
# gnuplot -e "data='contour_0.csv'; out='contour_0.png'; time_s=0.0004; R=0.127" \
#         freefem_scripts/plots/contour.gp
# data: rows x,y,uz (m) on a regular grid, x varying fastest (points outside the
# opening are not drawn); time_s: the time (s), R: the clamp edge's radius (m).
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 820,700 font ',11'
set output out
stats data using (column('x')) nooutput name 'X'
whole = X_min < 0
set title sprintf('Transverse displacement at t = %.3g s (%s)', time_s, whole ? 'whole specimen' : 'quarter model, cf. paper Fig. 11')
set xlabel 'x, along the warp (m)'
set ylabel 'y, along the weft (m)'
set cblabel 'transverse displacement u_z (m)'
set format x '%h'; set format y '%h'; set format cb '%h'
set size ratio -1
set xrange [X_min:X_max]; set yrange [X_min:X_max]
set palette cubehelix start 0.5 cycles -1.2 saturation 1.2 negative
set object 1 rectangle from graph 0, graph 0 to graph 1, graph 1 behind fillcolor rgb '#d9d9d9' fillstyle solid noborder
set label 1 'clamped' at R * 1.1, R * 1.25 front
set parametric; set trange [0:(whole ? 2 * pi : pi / 2)]; set samples 200
set key at graph 0.98, graph 0.98 box opaque
inside(x, y) = x**2 + y**2 <= R**2
plot data using (column('x')):(column('y')):(inside(column('x'), column('y')) ? column('uz') : NaN) \
        with image notitle, \
     R * cos(t), R * sin(t) with lines lw 2.5 lc rgb 'black' title sprintf('clamp edge, r = %g m', R)
