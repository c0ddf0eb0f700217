# explorer_stiffening.gp — the unit-cell explorer's biaxial stiffening: each yarn
# family's membrane stress against the strain along it, in the strip (the other
# edge free: crimp interchange lets the pulled family straighten at little load)
# and under equibiaxial stretch (the other family held stretched too: no
# interchange, the stiff yarns sooner), overlaid. Called by unit_cell_explorer.edp as
#   gnuplot -e "warp='warp.csv'; weft='weft.csv'; equi='equibiaxial.csv'; cols='...'; units='...'; heading='...'; out='stiffening.png'" explorer_stiffening.gp
# warp, weft  the strips' CSVs ('' for a strip not run: its panel is left out)
# equi        the equibiaxial path's CSV
# cols, units the paths' column names and units, space-separated, in the CSVs' order
#             (the three CSVs have the same columns, the first the nominal strain)
# heading     the title: cell, material, mode
# The values are the CSVs' as they are (SI); the axes say the columns' units.
set datafile separator ','
set datafile columnheaders
col_index(name) = (s = strstrt(" " . cols . " ", " " . name . " "), s > 0 ? words((" " . cols . " ")[1:s]) + 1 : 0)
unit(name) = col_index(name) > 0 ? word(units, col_index(name)) : "?"
panels = (warp ne '') + (weft ne '')
set terminal pngcairo size (panels > 1 ? 1400 : 800), 650 font ',11'
set output out
set multiplot layout 1, panels title heading noenhanced
set grid
set format x '%h'; set format y '%h'
set key left top box opaque
set xlabel "nominal strain ε along the family (" . word(units, 1) . ")"
if (warp ne '') {
    set title "warp: P_{11} against the warp strain"
    set ylabel "P_{11} (" . unit("P11") . ")"
    plot warp using 1:"P11" w l lw 2.5 lc 1 title "warp strip (weft edge free, P_{22} = 0)", \
         equi using 1:"P11" w l lw 2.5 dt 2 lc 1 title "equibiaxial (ε in both families)"
}
if (weft ne '') {
    set title "weft: P_{22} against the weft strain"
    set ylabel "P_{22} (" . unit("P22") . ")"
    plot weft using 1:"P22" w l lw 2.5 lc 2 title "weft strip (warp edge free, P_{11} = 0)", \
         equi using 1:"P22" w l lw 2.5 dt 2 lc 2 title "equibiaxial (ε in both families)"
}
unset multiplot
