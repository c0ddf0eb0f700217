# pack_study.gp — the pack study (bench/pack_study.sh): V50 and the back-face
# deformation against the pack's areal density (two y axes), and Cunniff's
# dimensionless form V50/U*^(1/3) against A_D A_p/m_p.
# gnuplot -e "data='study.csv'; out='study.png'" bench/pack_study.gp
# data: tools/cunniff.sh's CSV (plies,areal_density,v50,bfd,v50_over_ustar13,ad_ap_over_mp).
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1000,900 font ',11'
set output out
set multiplot layout 2, 1 title 'Pack ballistic limit (coarse mesh, 12.7 mm 0.104 kg hemispherical projectile)'
set grid
set xlabel 'areal density of the pack A_D (kg/m^2)'
set ylabel 'V50 (m/s)'
set y2label 'back-face deformation at the fastest stopped run (mm)'
set ytics nomirror; set y2tics
set key at graph 0.5, graph 0.95 center top box opaque horizontal
plot data using (column('areal_density')):(column('v50')) with linespoints pt 7 ps 1.5 lw 2 title 'V50', \
     '' using (column('areal_density')):(column('bfd') * 1e3) axes x1y2 with linespoints pt 5 ps 1.5 lw 2 dt 2 title 'BFD', \
     '' using (column('areal_density')):(column('v50')):(sprintf('%d', column('plies'))) with labels offset 0, 1 notitle
unset y2label; unset y2tics; set ytics mirror
set xlabel 'A_D A_p / m_p'
set ylabel 'V50 / U*^{1/3}'
set title "Cunniff's dimensionless form (U* = {/Symbol s}{/Symbol e}/(2{/Symbol r}) (E/{/Symbol r})^{1/2}, KM2 fibre)"
plot data using (column('ad_ap_over_mp')):(column('v50_over_ustar13')) with linespoints pt 7 ps 1.5 lw 2 title 'this model', \
     '' using (column('ad_ap_over_mp')):(column('v50_over_ustar13')):(sprintf('%d', column('plies'))) with labels offset 0, 1 notitle
unset multiplot
