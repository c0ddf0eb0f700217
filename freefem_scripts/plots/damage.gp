# damage.gp — the damaged region of a -failure on ballistic run at its end, seen
# from above in the reference plane, a panel per ply (strike face first), each
# titled with its ply: colour the larger yarn-family damage max(d1, d2) (0 intact
# .. 1 ruptured), black the eroded elements, the nose's outline (radius r) dashed
# round the impact point; axes in mm.
# gnuplot -e "data='damage.csv'; out='damage.png'; time_ms=0.3; r_mm=6.35; ax_mm=0; ay_mm=0; eroded_n=12;
#             plies=2; pack=1; cells=25921; layup='0 45'; eroded_ply='7 5'" freefem_scripts/plots/damage.gp
# data: rows ply,x_mm,y_mm,damage,eroded, a block of `cells` rows per ply on one
# regular grid, x varying fastest (eroded: the nodal erosion average >= 0.5, 1 or 0);
# pack: 1 when the run was given a pack option (the panels name ply, angle, eroded
# elements; layup and eroded_ply: a word per ply), 0 a single ply.
set datafile separator ','
set datafile columnheaders
columns = ceil(sqrt(plies)); rows = ceil(plies / (columns * 1.0))
set terminal pngcairo size (columns == 1 ? 820 : 520 * columns), (rows == 1 ? 700 : 460 * rows) \
    font (plies > 4 ? ',9' : ',11')
set output out
stats data using (column('x_mm')) nooutput name 'X'
stats data using (column('y_mm')) nooutput name 'Y'
whole = sprintf('Yarn damage at t = %.3g ms, %d elements eroded (black)', time_ms, eroded_n)
ply_role(p) = p == 0 ? ', strike face' : (p == plies - 1 ? ', back face' : '')
panel_title(p) = pack ? sprintf('ply %d (%s deg%s): %s elements eroded', p, word(layup, p + 1), ply_role(p), \
                                word(eroded_ply, p + 1)) : whole
set xlabel 'x, along the warp (mm)'
set ylabel 'y, along the weft (mm)'
set cblabel 'yarn damage max(d_1, d_2)'
set size ratio -1
set xrange [X_min:X_max]; set yrange [Y_min:Y_max]
set cbrange [0:1]
set palette defined (0 '#f7f7f7', 0.25 '#fee08b', 0.6 '#f46d43', 1 '#a50026')
set parametric; set trange [0:2 * pi]; set samples 200
set key at graph 0.98, graph 0.98 box opaque
if (pack) { set multiplot layout rows, columns title whole . ', ply by ply' }
do for [p = 0:plies - 1] {
    set title panel_title(p)
    if (p > 0) { unset key }   # (the nose's outline named once)
    plot data every ::(p * cells)::((p + 1) * cells - 1) using (column('x_mm')):(column('y_mm')):(column('damage')) \
            with image notitle, \
         '' every ::(p * cells)::((p + 1) * cells - 1) \
            using (column('x_mm')):(column('y_mm')):(0):(0):(0):(column('eroded') > 0.5 ? 255 : 0) \
            with rgbalpha notitle, \
         ax_mm + r_mm * cos(t), ay_mm + r_mm * sin(t) with lines lw 2 dt 2 lc rgb 'black' \
            title sprintf('nose, r = %g mm', r_mm)
}
if (pack) { unset multiplot }
