# explicit_loop.gp — the scripted central-difference loop against the built-in one:
# the apex (impact point) displacement of both, their difference, and the
# script's energy balance error against the built-in's.
# gnuplot -e "data='history.csv'; out='loop.png'" freefem_scripts/plots/explicit_loop.gp
# data: explicit_loop.edp's history.csv (columns addressed by name).
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1000,900 font ',11'
set output out
t_ms = '(column("time") * 1e3)'
set multiplot title 'Scripted explicit loop (explicit\_loop.edp) against the built-in integrator'
set lmargin 14; set rmargin 4
set grid
set autoscale xfix
set format x ''
set origin 0, 0.64; set size 1, 0.31
set ylabel 'apex displacement (mm)'
set key left top box opaque
plot data using (@t_ms):(column('apex_displacement') * 1e3) with lines lw 3 lc rgb '#1f77b4' \
        title 'scripted loop', \
     '' using (@t_ms):(column('apex_builtin') * 1e3) every 4 with points pt 7 ps 0.6 \
        lc rgb '#d62728' title 'built-in (every 4th frame)'
set origin 0, 0.34; set size 1, 0.30
set ylabel 'scripted - built-in (nm)'
set format y '%.1e'
plot data using (@t_ms):((column('apex_displacement') - column('apex_builtin')) * 1e9) \
        with lines lw 2 lc rgb '#2ca02c' title 'apex difference'
set origin 0, 0.02; set size 1, 0.32
set format x '%g'
set format y '%g'
set xlabel 'time (ms)'
set ylabel 'energy balance error (%)'
plot data using (@t_ms):(column('energy_error') * 100) with lines lw 2 lc rgb '#1f77b4' \
        title 'scripted (the script''s own balance)', \
     '' using (@t_ms):(column('energy_error_builtin') * 100) with lines lw 2 dt 2 \
        lc rgb '#d62728' title 'built-in (wovenffGet energy\_error)'
unset multiplot
