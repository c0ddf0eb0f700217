# ply_energy.gp — a pack's plies: the energy each ply has absorbed from the impact
# (absorbed_<p>: its kinetic + stored + dissipated energy, J, whole specimen, less
# its value at t = 0, the preload's stored energy) against time, with their sum
# and the ply contact's friction.
# gnuplot -e "data='history.csv'; out='ply_energy.png'; plies=8" freefem_scripts/plots/ply_energy.gp
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1000,650 font ',11'
set output out
set title sprintf('Energy absorbed by each ply (%d plies; ply 0 the strike face)', plies)
set xlabel 'time (s)'
set ylabel 'energy (J)'
set grid
set format x '%h'
set autoscale xfix
set key left top box opaque
set palette defined (0 '#1f77b4', 0.5 '#2ca02c', 1 '#ff7f0e'); set cbrange [0:1]; unset colorbox
array E0[plies]   # each ply's absorbed_<p> at t = 0 (the preload's stored energy)
do for [p = 0:plies - 1] {
    stats data using (column(sprintf('absorbed_%d', p))) every ::0::0 nooutput
    E0[p + 1] = STATS_min
}
absorbed(p) = column(sprintf('absorbed_%d', p)) - E0[p + 1]
total(p) = p < 0 ? 0 : absorbed(p) + total(p - 1)
set label 1 sprintf('less the preload energy at t = 0 (ply 0: %.3g J)', E0[1]) at graph 0.02, graph 0.6 front
plot for [p = 0:plies - 1] data using (column('time')):(absorbed(p)) \
        with lines lw 2 lc palette frac (plies > 1 ? p / (plies - 1.0) : 0) title sprintf('ply %d', p), \
     '' using (column('time')):(total(plies - 1)) with lines lw 3 lc rgb 'black' title 'all plies', \
     '' using (column('time')):(column('ply_contact_dissipated')) with lines lw 3 dt 2 lc rgb '#d62728' \
        title 'ply-ply friction'
