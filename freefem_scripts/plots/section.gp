# section.gp — the pack's cross-section through the point of impact: each ply's
# z (u_z, its plane starting at p gap) along +x at the profile times, z drawn
# downwards as the projectile moves (+z into the pack).
# gnuplot -e "data='section.csv'; out='section.png'; plies=8; times='0.0004 0.0009'; half=5e-6; gap=2.1e-4" \
#         freefem_scripts/plots/section.gp
# data: rows time,ply,position,z; times: the profile times (s) present; half:
# half the history interval (s), to match the times; gap: the plies' spacing (m).
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1100,700 font ',11'
set output out
set title sprintf("The pack's cross-section through the point of impact along x (%d plies, gap %.3g mm)", plies, gap * 1e3)
set xlabel 'distance from the point of impact (mm)'
set ylabel 'z (mm, +z: the projectile''s direction)'
set yrange [*:*] reverse
set grid
set key right bottom box opaque title 'colour: time; each ply a line'
at(t, p) = abs(column('time') - t) < half && column('ply') == p
set xrange [0:*]
plot for [i = 1:words(times)] for [p = 0:plies - 1] data \
        using (at(word(times, i) + 0, p) ? column('position') * 1e3 : NaN):(column('z') * 1e3) \
        with lines lw (p == 0 || p == plies - 1 ? 2.5 : 1) lc i \
        title (p == 0 ? sprintf('%.1f ms', word(times, i) * 1e3) : '')
