# contour.gp — transverse displacement of the quarter model (or, for a grid
# reaching x < 0, the whole specimen struck off the centre) at one time, seen
# from above (cf. the paper's Fig. 11): colour in mm, axes in mm, the clamp
# edge (the opening, r = R) drawn; the clamped fabric outside it is grey.
# gnuplot -e "data='contour_0.csv'; out='contour_0.png'; time_ms=0.4; R_mm=127" \
#         freefem_scripts/plots/contour.gp
# data: rows x_mm,y_mm,uz_mm on a regular grid, x varying fastest (points
# outside the opening are not drawn).
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 820,700 font ',11'
set output out
stats data using (column('x_mm')) nooutput name 'X'
whole = X_min < 0
set title sprintf('Transverse displacement at t = %.1f ms (%s)', time_ms, whole ? 'whole specimen' : 'quarter model, cf. paper Fig. 11')
set xlabel 'x, along the warp (mm)'
set ylabel 'y, along the weft (mm)'
set cblabel 'transverse displacement u_z (mm)'
set size ratio -1
set xrange [X_min:X_max]; set yrange [X_min:X_max]
set palette cubehelix start 0.5 cycles -1.2 saturation 1.2 negative
set object 1 rectangle from graph 0, graph 0 to graph 1, graph 1 behind fillcolor rgb '#d9d9d9' fillstyle solid noborder
set label 1 'clamped' at R_mm * 1.1, R_mm * 1.25 front
set parametric; set trange [0:(whole ? 2 * pi : pi / 2)]; set samples 200
set key at graph 0.98, graph 0.98 box opaque
inside(x, y) = x**2 + y**2 <= R_mm**2
plot data using (column('x_mm')):(column('y_mm')):(inside(column('x_mm'), column('y_mm')) ? column('uz_mm') : NaN) \
        with image notitle, \
     R_mm * cos(t), R_mm * sin(t) with lines lw 2.5 lc rgb 'black' title sprintf('clamp edge, r = %g mm', R_mm)
