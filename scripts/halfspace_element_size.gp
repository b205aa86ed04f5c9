# SPDX-License-Identifier: Apache-2.0
# Chart of the half-space element-size study: error against CONTACT and CPU time against the
# element size. Run from the repository root (scripts/halfspace_element_size_chart.sh):
#   gnuplot scripts/halfspace_element_size.gp
# Input docs/validation/halfspace_element_size.dat, output docs/validation/halfspace_element_size.png.
set terminal pngcairo size 1200,500 font "DejaVu Sans,10"
set output "docs/validation/halfspace_element_size.png"
set multiplot layout 1,2 title "Exact half-space model, S1002/UIC60 1:40, 78.5 kN: element size"
set grid
set key top left
set xlabel "element size [mm]"
set xrange [0.1:0.65]
set ylabel "|F - F_{CONTACT}| / (mu N) [%]"
set yrange [0:1]
set title "creep force against CONTACT (computed at 0.3 mm)"
f = "docs/validation/halfspace_element_size.dat"
plot f using 1:2 with linespoints title "dy -3, c\\_lat 0.001", \
     f using 1:3 with linespoints title "dy -3, e\\_combined", \
     f using 1:4 with linespoints title "dy 0, c\\_lat 0.001", \
     f using 1:5 with linespoints title "dy 0, e\\_combined", \
     f using 1:6 with linespoints title "dy +3, c\\_lat 0.001", \
     f using 1:7 with linespoints title "dy +3, e\\_combined"
set title "CPU time, central case (y = 0), normal + tangential"
set ylabel "CPU time per solve [ms]"
set logscale y
set yrange [1:500]
set key top right
plot f using 1:8 with linespoints title "before (928f1a7)", \
     f using 1:9 with linespoints title "after (exact model speed-up)"
unset multiplot
