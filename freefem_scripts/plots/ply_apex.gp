# ply_apex.gp — a pack's plies: each ply's largest transverse displacement
# (apex_<p>, u_z less the ply's initial offset p gap) and the back face (the
# last ply's) against time.
# gnuplot -e "data='history.csv'; out='ply_apex.png'; plies=8" freefem_scripts/plots/ply_apex.gp
# data: the ballistic scene's history.csv of a -plies run (columns addressed by name);
# the values as it holds them (SI: s, m).
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1000,650 font ',11'
set output out
set title sprintf('Apex displacement of each ply (%d plies; ply 0 the strike face)', plies)
set xlabel 'time (s)'
set ylabel 'largest transverse displacement (m)'
set grid
set format x '%h'; set format y '%h'
set autoscale xfix
set key left top box opaque
set palette defined (0 '#1f77b4', 0.5 '#2ca02c', 1 '#ff7f0e'); set cbrange [0:1]; unset colorbox
plot for [p = 0:plies - 1] data using (column('time')):(column(sprintf('apex_%d', p))) \
        with lines lw 2 lc palette frac (plies > 1 ? p / (plies - 1.0) : 0) title sprintf('ply %d', p), \
     '' using (column('time')):(column('back_face')) with lines lw 4 dt 2 lc rgb 'black' \
        title 'back face (the last ply)'
