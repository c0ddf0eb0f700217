# explicit_loop.gp — the scripted central-difference loop against the built-in one:
# the apex (impact point) displacement of both, their difference, and the
# script's energy balance error against the built-in's.
# gnuplot -e "data='history.csv'; out='loop.png'" freefem_scripts/plots/explicit_loop.gp
# data: explicit_loop.edp's history.csv (columns addressed by name); the values as
# it holds them (SI: s, m; the balance errors fractions).
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1000,900 font ',11'
set output out
t_s = '(column("time"))'
set multiplot title 'Scripted explicit loop (explicit\_loop.edp) against the built-in integrator'
set lmargin 14; set rmargin 4
set grid
set autoscale xfix
set format x ''
set origin 0, 0.64; set size 1, 0.31
set ylabel 'apex displacement (m)'
set format y '%h'
set key left top box opaque
plot data using (@t_s):(column('apex_displacement')) with lines lw 3 lc rgb '#1f77b4' \
        title 'scripted loop', \
     '' using (@t_s):(column('apex_builtin')) every 4 with points pt 7 ps 0.6 \
        lc rgb '#d62728' title 'built-in (every 4th frame)'
set origin 0, 0.34; set size 1, 0.30
set ylabel 'scripted - built-in (m)'
set format y '%.1e'
plot data using (@t_s):(column('apex_displacement') - column('apex_builtin')) \
        with lines lw 2 lc rgb '#2ca02c' title 'apex difference'
set origin 0, 0.02; set size 1, 0.32
set format x '%h'
set format y '%h'
set xlabel 'time (s)'
set ylabel 'energy balance error (-)'
plot data using (@t_s):(column('energy_error')) with lines lw 2 lc rgb '#1f77b4' \
        title 'scripted (the script''s own balance)', \
     '' using (@t_s):(column('energy_error_builtin')) with lines lw 2 dt 2 \
        lc rgb '#d62728' title 'built-in (wovenffGet energy\_error)'
unset multiplot
