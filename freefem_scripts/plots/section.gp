# section.gp — the pack's cross-section through the point of impact: each ply's
# z (u_z, its plane starting at p gap) along +x at the profile times and at the
# run's end, z upwards (+z: the projectile's direction). The z scale is the plies'
# attached fabric (fabric 1) and their planes (z = 0): fragments torn off
# (fabric 0) are marked (grey x) where they fall inside it and counted in the key,
# eroded elements (fabric -1: holes) are left out. The projectile's tip at each
# time is a triangle on the axis (x = 0), inside the scale too.
# gnuplot -e "data='section.csv'; out='section.png'; plies=8; times='0.0004 0.0009 0.00121'; half=5e-6;
#             gap=2.1e-4; tend=0.00121; tips='0.017 0.05 0.066'" \
#         freefem_scripts/plots/section.gp
# data: rows time,ply,position,z,fabric; times: the section times (s) present;
# half: half the history interval (s), to match the times; gap: the plies'
# spacing (m); tend: the run's end time (s; its line says "the end"); tips: the
# projectile's tip (m, its z) at each of the times. The values are the CSV's as
# they are (SI: m, the times in s); the tips, not in section.csv, are marks (labels
# with a point) on the axis, not curves.
set datafile separator ','
# a number from its text: gnuplot reads "2e-05" + 0 as 2 followed by junk (an error), so a
# mantissa without a point gets one
num(s) = (p_ = strstrt(s, "e"), p_ > 0 && strstrt(s, ".") == 0 ? (s[1:p_ - 1] . ".0" . s[p_:]) + 0 : s + 0)
set datafile columnheaders
set terminal pngcairo size 1100,700 font ',11'
set output out
stats data using (column('fabric') == 1 ? column('z') : 0) nooutput name 'A'
stats data using (column('position')) nooutput name 'X'   # (before any range is set: stats keeps to it)
zmin = A_min; zmax = A_max
do for [i = 1:words(tips)] { tip = num(word(tips, i)); zmin = tip < zmin ? tip : zmin; zmax = tip > zmax ? tip : zmax }
span = zmax - zmin > 1e-6 ? zmax - zmin : 1e-3
zlow = zmin - 0.05 * span; zhigh = zmax + 0.05 * span
inside(z) = z >= zlow && z <= zhigh
stats data using (column('fabric') == 0 ? 1 : 0) nooutput name 'F'
stats data using (column('fabric') == 0 && !inside(column('z')) ? 1 : 0) nooutput name 'FOUT'
stats data using (column('fabric') == -1 ? 1 : 0) nooutput name 'E'
set title sprintf("The pack's cross-section through the point of impact along x (%d plies, gap %.3g m)\nthe attached fabric; eroded elements (%d points) left out", \
                  plies, gap, E_sum)
set xlabel 'distance from the point of impact (m)'
set ylabel 'z (m, up: the projectile''s direction +z)'
set format x '%h'; set format y '%h'
set yrange [zlow:zhigh]
set grid
set key right top box opaque title 'colour: time; each ply a line'
at(t, p) = abs(column('time') - t) < half && column('ply') == p
label(t) = sprintf('t = %.3g s%s', t, abs(t - tend) < half ? ' (the end)' : '')
set xrange [-0.015 * X_max:X_max]   # (room for the tips on the axis)
# the tips: a mark on the axis at each time, in the time's colour
do for [i = 1:words(tips)] { set label 100 + i '' at 0, num(word(tips, i)) point pt 9 ps 2.2 lc i front }
plot for [i = 1:words(times)] for [p = 0:plies - 1] data \
        using (at(num(word(times, i)), p) && column('fabric') == 1 ? column('position') : NaN):(column('z')) \
        with lines lw (p == 0 || p == plies - 1 ? 2.5 : 1) lc i \
        title (p == 0 ? label(num(word(times, i))) : ''), \
     data using (column('fabric') == 0 ? column('position') : NaN):(column('z')) \
        with points pt 2 ps 0.7 lc rgb '#808080' \
        title (F_sum > 0 ? sprintf('fragments torn off: %d points, %d beyond this scale', F_sum, FOUT_sum) : ''), \
     NaN with points pt 9 ps 2.2 lc rgb 'black' title "the projectile's tip (colour: time)"
