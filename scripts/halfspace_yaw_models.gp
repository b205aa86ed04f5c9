# SPDX-License-Identifier: Apache-2.0
# Chart of the fast models and the exact half-space model against CONTACT on the Manchester case
# A-2.2 as the yaw grows. Run from the repository root through scripts/halfspace_yaw_chart.sh,
# which writes the input docs/validation/halfspace_yaw_models.dat; output
# docs/validation/halfspace_yaw_models.png.
set terminal pngcairo size 1200,500 font "DejaVu Sans,10"
set output "docs/validation/halfspace_yaw_models.png"
set multiplot layout 1,2 title "S1002 on UIC60, Manchester case A-2.2 (yaw and lateral shift grow together: Y = yaw / 2.4 mrad/mm), creep force against CONTACT"
set grid
set xlabel "yaw [mrad]"
set xrange [-0.5:24.5]
set ylabel "|F - F_{CONTACT}| / (mu N) [%]"
set logscale y
set yrange [0.005:50]
set label 1 "a value printed as 0 is drawn at the floor" at graph 0.98, graph 0.03 right font ",8"
set format y "%g"
set key bmargin center horizontal font ",9"
# A value printed as 0 (below the reports' last digit: 0.1 % fast models, 0.01 % exact model) is drawn
# at the floor of the axis.
shown(v) = v > 0 ? v : 0.005
f = "docs/validation/halfspace_yaw_models.dat"
set title "left wheel (tread contact)"
plot f using (strcol(1) eq "left" ? $3 : NaN):(shown($5)) with linespoints pt 4 title "Hertz", \
     f using (strcol(1) eq "left" ? $3 : NaN):(shown($6)) with linespoints pt 6 title "Kik-Piotrowski", \
     f using (strcol(1) eq "left" ? $3 : NaN):(shown($7)) with linespoints pt 8 title "Linder", \
     f using (strcol(1) eq "left" ? $3 : NaN):(shown($8)) with linespoints pt 10 title "STRIPES A", \
     f using (strcol(1) eq "left" ? $3 : NaN):(shown($9)) with linespoints pt 12 title "STRIPES A&B" noenhanced, \
     f using (strcol(1) eq "left" ? $3 : NaN):(shown($10)) with linespoints lw 2 lc rgb "black" pt 7 title "exact half-space"
set title "right wheel (tread contact, flange contact from 14.4 mrad: shaded)"
set object 1 rect from 14.0, graph 0 to 24.5, graph 1 behind fillcolor rgb "#eeeeee" fillstyle solid noborder
plot f using (strcol(1) eq "right" ? $3 : NaN):(shown($5)) with linespoints pt 4 title "Hertz", \
     f using (strcol(1) eq "right" ? $3 : NaN):(shown($6)) with linespoints pt 6 title "Kik-Piotrowski", \
     f using (strcol(1) eq "right" ? $3 : NaN):(shown($7)) with linespoints pt 8 title "Linder", \
     f using (strcol(1) eq "right" ? $3 : NaN):(shown($8)) with linespoints pt 10 title "STRIPES A", \
     f using (strcol(1) eq "right" ? $3 : NaN):(shown($9)) with linespoints pt 12 title "STRIPES A&B" noenhanced, \
     f using (strcol(1) eq "right" ? $3 : NaN):(shown($10)) with linespoints lw 2 lc rgb "black" pt 7 title "exact half-space"
unset multiplot
