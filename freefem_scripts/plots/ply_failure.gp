# ply_failure.gp — a pack's failure sequence: the energy each ply has absorbed from
# the impact (absorbed_<p>, J, less its value at t = 0) against time (s), with a
# dashed line in the ply's colour at the time its first yarn was damaged (the
# module's ply value first_damage_time; -1: the ply stayed intact, no line).
# gnuplot -e "data='history.csv'; out='ply_failure.png'; plies=4; damaged='7.4e-4 8.2e-4 -1 -1'" freefem_scripts/plots/ply_failure.gp
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1000,650 font ',11'
set output out
set title sprintf('Failure sequence: energy absorbed by each ply, dashed at its first yarn damage (%d plies; ply 0 the strike face)', plies) font ',10'
set xlabel 'time (s)'
set format x '%h'
set ylabel 'energy absorbed by the ply (J)'
set grid
set autoscale xfix
set key left top box opaque
set palette defined (0 '#1f77b4', 0.5 '#2ca02c', 1 '#ff7f0e'); set cbrange [0:1]; unset colorbox
array E0[plies]
do for [p = 0:plies - 1] {
    stats data using (column(sprintf('absorbed_%d', p))) every ::0::0 nooutput
    E0[p + 1] = STATS_min
}
absorbed(p) = column(sprintf('absorbed_%d', p)) - E0[p + 1]
frac(p) = plies > 1 ? p / (plies - 1.0) : 0
intact = 0
do for [p = 0:plies - 1] {
    t = real(word(damaged, p + 1))
    if (t >= 0) {
        set arrow (p + 1) from first t, graph 0 to first t, graph 1 nohead dt 2 lw 1.5 lc palette frac frac(p)
    } else {
        intact = intact + 1
    }
}
set label 1 sprintf('%d of %d plies never damaged', intact, plies) at graph 0.98, graph 0.05 right front
plot for [p = 0:plies - 1] data using (column('time')):(absorbed(p)) \
        with lines lw 2 lc palette frac frac(p) title sprintf('ply %d', p)
