# explorer_cell.gp — the unit-cell explorer's 3-D picture of the crimped cell at
# four levels of a path: half-yarn trusses from the cell edge to the crossover
# (warp up to +A_1, weft down to −A_2), the crossover spring and the locking
# spars (in-plane length s_k = J/p_k, height A_k; colour: force). Called by
# unit_cell_explorer.edp as
#   gnuplot -e "dat='cell_P.dat'; out='cell_P.png'; path='shear'; heading='...'; p1=3.735e-4; p2=3.735e-4" explorer_cell.gp
# dat      one row per level: load F11 F12 F21 F22 A1 A2 dA1 dA2 F_L1 F_L2
#          (the load in the unit of the path's CSV; F in-plane, -; A, dA in m; spar forces in N)
# heading  the title: path, cell, material, mode
# p1, p2   the reference quarter wavelengths p_k⁰ (m, the cell's reference_geometry)
# Lengths in m, as in the CSVs (SI): x, y to scale, z (height) stretched.

# the level's geometry into G1x..F2y (g_k = F E_k p_k⁰; f_k the foot of the
# perpendicular from the other yarn's end on yarn k); returns its argument
geom(d) = (G1x = p1 * column(2), G1y = p1 * column(4), G2x = p2 * column(3), G2y = p2 * column(5), \
           A1 = column(6), A2 = column(7), dot = G1x * G2x + G1y * G2y, \
           F1x = dot / (G1x**2 + G1y**2) * G1x, F1y = dot / (G1x**2 + G1y**2) * G1y, \
           F2x = dot / (G2x**2 + G2y**2) * G2x, F2y = dot / (G2x**2 + G2y**2) * G2y, d)

# view ranges from every level (the cell edge and the heights), with a margin
stats dat using (geom(0), abs(G1x) + abs(G2x)) name "SX" nooutput
stats dat using (geom(0), abs(G1y) + abs(G2y)) name "SY" nooutput
stats dat using 6 name "SA1" nooutput
stats dat using 7 name "SA2" nooutput
stats dat using (column(10) > column(11) ? column(10) : column(11)) name "SF" nooutput
xy = 1.08 * (SX_max > SY_max ? SX_max : SY_max)
zpad = 0.2 * (SA1_max + SA2_max)
# each level's load, ΔA and spar forces for the titles (round-off shown as 0)
array Q[4]; array D1[4]; array D2[4]; array L1[4]; array L2[4]
stats dat using (r = int($0) + 1, Q[r] = $1, D1[r] = $8, D2[r] = $9, L1[r] = $10, L2[r] = $11, 0) nooutput
clean(v, small) = abs(v) < small ? 0 : v

set terminal pngcairo size 1400,1050 font ',10'
set output out
set multiplot title "The unit cell, " . heading . "\nhalf-yarn trusses from the cell edge to the crossover, " \
    . "crossover spring, locking spars (colour: force); x, y to scale, z (height) stretched" noenhanced
set view 70, 30, 1.0; set view equal xy; set xyplane relative 0
set border 4095 lc rgb "gray70"; set tics textcolor "black"   # the whole box: every segment ends visibly inside it
raw = xy / 2; mag = 10**floor(log10(raw))   # about four tics across the cell
tic = raw / mag >= 5 ? 5 * mag : raw / mag >= 2 ? 2 * mag : mag
set xtics tic; set ytics tic
set format x '%h'; set format y '%h'; set format z '%h'
set xrange [-xy:xy]; set yrange [-xy:xy]; set zrange [-SA2_max - zpad:SA1_max + zpad]
set xlabel "x, warp (m)"; set ylabel "y, weft (m)"; set zlabel "z (m)" rotate parallel offset -4, 0
set palette defined (0 '#c0c0c0', 0.3 '#ff9900', 1 '#dd0000')
set cbrange [0:(SF_max > 1e-3 ? SF_max : 1e-3)]; set cblabel "spar force F_L (N)"
set colorbox user origin screen 0.88, screen 0.22 size screen 0.02, screen 0.35
unset key; set ticslevel 0
load_text(q) = path eq "equalforce" ? sprintf("T = %.3g N", q) : \
               path eq "shear" ? sprintf("γ = %.3g rad", q) : sprintf("ε = %.3g", q)
do for [k = 0:3] {
    set origin 0.41 * (k % 2), (k < 2 ? 0.46 : 0.0); set size 0.41, 0.46
    set title sprintf("%s:  ΔA_1 = %.3g, ΔA_2 = %.3g m,  F_{L1} = %.3g, F_{L2} = %.3g N", \
        load_text(Q[k + 1]), clean(D1[k + 1], 1e-15), clean(D2[k + 1], 1e-15), clean(L1[k + 1], 1e-12), clean(L2[k + 1], 1e-12))
    splot for [sg = -1:1:2] dat every ::k::k using (geom(sg * (G1x + G2x))):(sg * (G1y + G2y)):(0):(-2 * sg * G2x):(-2 * sg * G2y):(0) \
              w vectors nohead lc rgb 'gray50' dt 2, \
          for [sg = -1:1:2] dat every ::k::k using (geom(sg * (G1x - G2x))):(sg * (G1y - G2y)):(0):(-2 * sg * G1x):(-2 * sg * G1y):(0) \
              w vectors nohead lc rgb 'gray50' dt 2, \
          for [sg = -1:1:2] dat every ::k::k using (geom(sg * G1x)):(sg * G1y):(0):(-sg * G1x):(-sg * G1y):(A1) \
              w vectors nohead lw 4 lc rgb '#1f5fbf', \
          for [sg = -1:1:2] dat every ::k::k using (geom(sg * G2x)):(sg * G2y):(0):(-sg * G2x):(-sg * G2y):(-A2) \
              w vectors nohead lw 4 lc rgb '#e07b00', \
          dat every ::k::k using (geom(0)):(0):(A1):(0):(0):(-A1 - A2) w vectors nohead lw 3 lc rgb '#2a9d2a', \
          for [sg = -1:1:2] dat every ::k::k using (geom(sg * G2x)):(sg * G2y):(0):(sg * (F1x - G2x)):(sg * (F1y - G2y)):(0) \
              w vectors nohead lw 1 lc rgb 'gray40' dt 3, \
          for [sg = -1:1:2] dat every ::k::k using (geom(sg * G1x)):(sg * G1y):(0):(sg * (F2x - G1x)):(sg * (F2y - G1y)):(0) \
              w vectors nohead lw 1 lc rgb 'gray40' dt 3, \
          for [sg = -1:1:2] dat every ::k::k using (geom(sg * G2x)):(sg * G2y):(0):(sg * (F1x - G2x)):(sg * (F1y - G2y)):(A1):10 \
              w vectors nohead lw 2 lc palette, \
          for [sg = -1:1:2] dat every ::k::k using (geom(sg * G1x)):(sg * G1y):(0):(sg * (F2x - G1x)):(sg * (F2y - G1y)):(-A2):11 \
              w vectors nohead lw 2 lc palette
}
# the legend, in a panel of its own beside the pictures
set origin 0.80, 0.62; set size 0.19, 0.26; unset title; unset border; unset tics
unset xlabel; unset ylabel; unset zlabel; unset colorbox
set key center center box Left reverse samplen 2
set xrange [0:1]; set yrange [0:1]
plot NaN w l lc rgb 'gray50' dt 2 title "cell edge (2p_1 × 2p_2)", \
     NaN w l lw 4 lc rgb '#1f5fbf' title "warp half-yarns", \
     NaN w l lw 4 lc rgb '#e07b00' title "weft half-yarns", \
     NaN w l lw 3 lc rgb '#2a9d2a' title "crossover (compaction) spring", \
     NaN w l lw 2 lc rgb '#dd0000' title "locking spars", \
     NaN w l lw 1 lc rgb 'gray40' dt 3 title "spar gap s_k = J/p_k"
unset multiplot
