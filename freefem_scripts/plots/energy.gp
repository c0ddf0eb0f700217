# energy.gp — where the energy of the ballistic run goes (whole specimen), and
# the balance error in a panel of its own.
# gnuplot -e "data='history.csv'; out='energy.png'; mechs='yarn_stretch yarn_bending'" \
#         freefem_scripts/plots/energy.gp
# data: the ballistic scene's history.csv; mechs: the cell's mechanisms
# (columns energy_<name>), space-separated; failure=1 (a -failure on run): the
# columns failure_energy and eroded_energy drawn too. The values are the CSV's as
# they are (SI: time in s, energies in J, the balance error a fraction).
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1100,800 font ',11'
set output out
if (!exists('failure')) failure = 0
failure_curves = failure ? ", '' using @t_s:(column('failure_energy')) with lines lw 3 lc rgb '#a50026' title 'failure (yarn damage)', " \
    . "'' using @t_s:(column('eroded_energy')) with lines lw 3 lc rgb '#555555' title 'in eroded elements'" : ""
stats data using (column('internal_energy')) every ::0::0 nooutput name 'START'
t_s = '(column("time"))'
set multiplot title 'Energy of the impact (whole specimen); thin dashed: stored energy by mechanism'
set lmargin 12; set rmargin 34
set grid
set autoscale xfix
set origin 0, 0.30; set size 1, 0.64
set ylabel 'energy (J)'
set format x ''
set key outside right top
set label 1 sprintf("stored at t = 0: %.2f J,\nthe preload's energy", START_min) \
    at graph 0.02, graph 0.93 front
plot data using @t_s:(column('kinetic_projectile')) with lines lw 3 title 'projectile kinetic', \
     '' using @t_s:(column('kinetic_energy') - column('kinetic_projectile')) with lines lw 3 \
        title 'fabric kinetic', \
     '' using @t_s:(column('internal_energy')) with lines lw 3 title 'stored (cells)', \
     '' using @t_s:(column('dissipated_energy')) with lines lw 3 title 'dissipated', \
     for [m in mechs] '' using @t_s:(column('energy_'.m)) with lines lw 1.5 dt 2 \
        title 'stored: '.m noenhanced @failure_curves
unset label 1
set origin 0, 0.02; set size 1, 0.30
set format x '%h'
set xlabel 'time (s)'
set ylabel 'balance error (-)'
set format y '%.1e'
plot data using @t_s:(column('energy_error')) with lines lw 2 lc rgb 'black' \
        title 'energy balance error'
unset multiplot
