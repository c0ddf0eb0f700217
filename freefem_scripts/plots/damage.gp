# damage.gp — the damaged region of a -failure on ballistic run at its end, seen
# from above in the reference plane, a panel per ply (strike face first), each
# titled with its ply: colour the larger yarn-family damage max(d1, d2) (0 intact
# .. 1 ruptured), black the eroded elements, the nose's outline (radius r) dashed
# round the impact point; axes in m, as the CSV holds them.
# gnuplot -e "data='damage.csv'; out='damage.png'; time_s=0.0003; r=0.00635; ax=0; ay=0; eroded_n=12;
#             plies=2; pack=1; cells=25921; layup='0 45'; eroded_ply='7 5'" freefem_scripts/plots/damage.gp
# data: rows ply,x,y,damage,eroded (x, y in m), a block of `cells` rows per ply on one
# regular grid, x varying fastest (eroded: the nodal erosion average >= 0.5, 1 or 0);
# pack: 1 when the run was given a pack option (the panels name ply, angle, eroded
# elements; layup and eroded_ply: a word per ply), 0 a single ply.
set datafile separator ','
set datafile columnheaders
columns = ceil(sqrt(plies)); rows = ceil(plies / (columns * 1.0))
set terminal pngcairo size (columns == 1 ? 820 : 520 * columns), (rows == 1 ? 700 : 460 * rows) \
    font (plies > 4 ? ',9' : ',11')
set output out
stats data using (column('x')) nooutput name 'X'
stats data using (column('y')) nooutput name 'Y'
whole = sprintf('Yarn damage at t = %.3g s, %d elements eroded (black)', time_s, eroded_n)
ply_role(p) = p == 0 ? ', strike face' : (p == plies - 1 ? ', back face' : '')
panel_title(p) = pack ? sprintf('ply %d (%s deg%s): %s elements eroded', p, word(layup, p + 1), ply_role(p), \
                                word(eroded_ply, p + 1)) : whole
set xlabel 'x, along the warp (m)'
set ylabel 'y, along the weft (m)'
set cblabel 'yarn damage max(d_1, d_2) (-)'
set format x '%h'; set format y '%h'
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
    plot data every ::(p * cells)::((p + 1) * cells - 1) using (column('x')):(column('y')):(column('damage')) \
            with image notitle, \
         '' every ::(p * cells)::((p + 1) * cells - 1) \
            using (column('x')):(column('y')):(0):(0):(0):(column('eroded') > 0.5 ? 255 : 0) \
            with rgbalpha notitle, \
         ax + r * cos(t), ay + r * sin(t) with lines lw 2 dt 2 lc rgb 'black' \
            title sprintf('nose, r = %g m', r)
}
if (pack) { unset multiplot }
