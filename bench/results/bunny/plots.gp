# Written by `ellicast compare`: run `gnuplot plots.gp` in this folder to redraw the plots.
set datafile missing 'NaN'
set key outside bottom center horizontal maxrows 1
set bmargin 6
set grid
set style line 1 lw 2 dt 1 pt 5 ps 0.8 lc rgb '#d62728'
set style line 2 lw 2 dt 2 pt 7 ps 0.8 lc rgb '#1f77b4'
set style line 3 lw 2 dt 3 pt 9 ps 0.8 lc rgb '#2ca02c'
set style line 4 lw 2 dt 4 pt 11 ps 0.8 lc rgb '#9467bd'
$loss0_shown << EOD
0 100 0 0 100 0 0 100 0 0 100 0 0
5 100 0 0 85 0 0 100 0 0 100 0 0
10 100 0 0 55 0 0 100 0 0 100 0 0
20 100 0 0 15 0 0 100 0 0 100 0 0
30 100 0 0 0 0 0 100 0 0 100 0 0
50 100 0 0 0 0 0 0 0 0 100 0 0
70 100 0 0 0 0 0 0 0 0 100 0 0
EOD
$loss0_holes << EOD
0 0 0 0 0 0 0 0 0 0 0 0 0
5 0 0 0.0005023 0 0 0 0 0 0 0.8238 0.6495 1.484
10 0 0 0.002009 0 0 100 0 0 0 2.173 1.158 2.753
20 0.004019 0 0.006028 100 100 100 0 0 0 4.786 4.254 5.653
30 0.01306 0.004019 0.01859 100 100 100 0 0 0 9.533 7.844 11.6
50 0.03516 0.03014 0.05174 100 100 100 100 100 100 24.74 21.44 25.63
70 0.1286 0.1075 0.1577 100 100 100 100 100 100 44.73 42.56 47.12
EOD
$loss0_rms << EOD
0 0.01065 0.01065 0.01065 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007756 0.0007756 0.0007756
5 0.01429 0.01391 0.01519 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.1717 0.152 0.2243
10 0.01582 0.0155 0.01622 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.2698 0.1633 0.3157
20 0.01987 0.01964 0.02142 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.4067 0.3648 0.4534
30 0.02414 0.02195 0.02551 NaN NaN NaN 0.0007721 0.0007721 0.0007721 0.6537 0.5537 0.7528
50 0.03531 0.0344 0.03679 NaN NaN NaN NaN NaN NaN 1.218 1.145 1.397
70 0.05628 0.05332 0.06107 NaN NaN NaN NaN NaN NaN 2.37 2.199 2.896
EOD
$time1_shown << EOD
0.25 100 0 0 0 0 0 0 0 0 100 0 0
0.5 100 0 0 0 0 0 95 0 0 100 0 0
1 100 0 0 55 0 0 100 0 0 100 0 0
2 100 0 0 100 0 0 100 0 0 100 0 0
EOD
$time1_holes << EOD
0.25 0.1738 0.1442 0.2245 100 100 100 100 100 100 57.11 56.06 58.86
0.5 0.03717 0.02813 0.05375 100 100 100 0 0 0 17.11 16.43 18.55
1 0 0 0.002009 0 0 100 0 0 0 2.173 1.158 2.753
2 0 0 0 0 0 0 0 0 0 0 0 0
EOD
$time1_rms << EOD
0.25 0.07036 0.06523 0.07661 NaN NaN NaN NaN NaN NaN 7.781 7.406 9.243
0.5 0.03673 0.03538 0.03888 NaN NaN NaN 0.0007721 0.0007721 0.0007721 1.512 1.456 1.844
1 0.01582 0.0155 0.01622 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.2698 0.1633 0.3157
2 0.01315 0.01289 0.0135 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007756 0.0007756 0.0007756
EOD
$time2_shown << EOD
0.25 60 0 0 0 0 0 0 0 0 100 0 0
0.5 95 0 0 0 0 0 0 0 0 100 0 0
1 100 0 0 0 0 0 0 0 0 100 0 0
2 100 0 0 5 0 0 100 0 0 100 0 0
EOD
$time2_holes << EOD
0.25 1.458 0.7646 100 100 100 100 100 100 100 72.94 70.08 74.75
0.5 0.1618 0.1266 0.2004 100 100 100 100 100 100 47.17 44.97 50.11
1 0.03516 0.03014 0.05174 100 100 100 100 100 100 24.74 21.44 25.63
2 0.003014 0.001507 0.01005 100 100 100 0 0 0 7.388 6.427 8.396
EOD
$time2_rms << EOD
0.25 0.1179 0.1111 0.1325 NaN NaN NaN NaN NaN NaN 9.106 8.528 12.43
0.5 0.06445 0.05976 0.06855 NaN NaN NaN NaN NaN NaN 2.775 2.451 3.184
1 0.03531 0.0344 0.03679 NaN NaN NaN NaN NaN NaN 1.218 1.145 1.397
2 0.02156 0.02042 0.02291 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.4877 0.4468 0.638
EOD
set terminal svg size 1500,480 dynamic font 'Helvetica,13'
set output 'loss_one_cycle.svg'
set multiplot layout 1,3 title 'After one cycle, independent loss (median, bars: quartiles)'
set xlabel 'packets lost (%)'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $loss0_shown using ($1+-0.75):2 with linespoints ls 1 title 'ellicast', $loss0_shown using ($1+-0.25):5 with linespoints ls 2 title 'draco-whole', $loss0_shown using ($1+0.25):8 with linespoints ls 3 title 'draco-fec', $loss0_shown using ($1+0.75):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $loss0_holes using ($1+-0.75):2:3:4 with yerrorlines ls 1 title 'ellicast', $loss0_holes using ($1+-0.25):5:6:7 with yerrorlines ls 2 title 'draco-whole', $loss0_holes using ($1+0.25):8:9:10 with yerrorlines ls 3 title 'draco-fec', $loss0_holes using ($1+0.75):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $loss0_rms using ($1+-0.75):2:3:4 with yerrorlines ls 1 title 'ellicast', $loss0_rms using ($1+-0.25):5:6:7 with yerrorlines ls 2 title 'draco-whole', $loss0_rms using ($1+0.25):8:9:10 with yerrorlines ls 3 title 'draco-fec', $loss0_rms using ($1+0.75):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal pngcairo size 1500,480 font 'Helvetica,11'
set output 'loss_one_cycle.png'
set multiplot layout 1,3 title 'After one cycle, independent loss (median, bars: quartiles)'
set xlabel 'packets lost (%)'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $loss0_shown using ($1+-0.75):2 with linespoints ls 1 title 'ellicast', $loss0_shown using ($1+-0.25):5 with linespoints ls 2 title 'draco-whole', $loss0_shown using ($1+0.25):8 with linespoints ls 3 title 'draco-fec', $loss0_shown using ($1+0.75):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $loss0_holes using ($1+-0.75):2:3:4 with yerrorlines ls 1 title 'ellicast', $loss0_holes using ($1+-0.25):5:6:7 with yerrorlines ls 2 title 'draco-whole', $loss0_holes using ($1+0.25):8:9:10 with yerrorlines ls 3 title 'draco-fec', $loss0_holes using ($1+0.75):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $loss0_rms using ($1+-0.75):2:3:4 with yerrorlines ls 1 title 'ellicast', $loss0_rms using ($1+-0.25):5:6:7 with yerrorlines ls 2 title 'draco-whole', $loss0_rms using ($1+0.25):8:9:10 with yerrorlines ls 3 title 'draco-fec', $loss0_rms using ($1+0.75):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal svg size 1500,480 dynamic font 'Helvetica,13'
set output 'time_loss10.svg'
set multiplot layout 1,3 title '10% of packets lost, independent loss (median, bars: quartiles)'
set xlabel 'cycles after tune-in'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $time1_shown using ($1+-0.03):2 with linespoints ls 1 title 'ellicast', $time1_shown using ($1+-0.01):5 with linespoints ls 2 title 'draco-whole', $time1_shown using ($1+0.01):8 with linespoints ls 3 title 'draco-fec', $time1_shown using ($1+0.03):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $time1_holes using ($1+-0.03):2:3:4 with yerrorlines ls 1 title 'ellicast', $time1_holes using ($1+-0.01):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time1_holes using ($1+0.01):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time1_holes using ($1+0.03):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $time1_rms using ($1+-0.03):2:3:4 with yerrorlines ls 1 title 'ellicast', $time1_rms using ($1+-0.01):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time1_rms using ($1+0.01):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time1_rms using ($1+0.03):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal pngcairo size 1500,480 font 'Helvetica,11'
set output 'time_loss10.png'
set multiplot layout 1,3 title '10% of packets lost, independent loss (median, bars: quartiles)'
set xlabel 'cycles after tune-in'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $time1_shown using ($1+-0.03):2 with linespoints ls 1 title 'ellicast', $time1_shown using ($1+-0.01):5 with linespoints ls 2 title 'draco-whole', $time1_shown using ($1+0.01):8 with linespoints ls 3 title 'draco-fec', $time1_shown using ($1+0.03):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $time1_holes using ($1+-0.03):2:3:4 with yerrorlines ls 1 title 'ellicast', $time1_holes using ($1+-0.01):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time1_holes using ($1+0.01):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time1_holes using ($1+0.03):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $time1_rms using ($1+-0.03):2:3:4 with yerrorlines ls 1 title 'ellicast', $time1_rms using ($1+-0.01):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time1_rms using ($1+0.01):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time1_rms using ($1+0.03):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal svg size 1500,480 dynamic font 'Helvetica,13'
set output 'time_loss50.svg'
set multiplot layout 1,3 title '50% of packets lost, independent loss (median, bars: quartiles)'
set xlabel 'cycles after tune-in'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $time2_shown using ($1+-0.03):2 with linespoints ls 1 title 'ellicast', $time2_shown using ($1+-0.01):5 with linespoints ls 2 title 'draco-whole', $time2_shown using ($1+0.01):8 with linespoints ls 3 title 'draco-fec', $time2_shown using ($1+0.03):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $time2_holes using ($1+-0.03):2:3:4 with yerrorlines ls 1 title 'ellicast', $time2_holes using ($1+-0.01):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time2_holes using ($1+0.01):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time2_holes using ($1+0.03):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $time2_rms using ($1+-0.03):2:3:4 with yerrorlines ls 1 title 'ellicast', $time2_rms using ($1+-0.01):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time2_rms using ($1+0.01):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time2_rms using ($1+0.03):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal pngcairo size 1500,480 font 'Helvetica,11'
set output 'time_loss50.png'
set multiplot layout 1,3 title '50% of packets lost, independent loss (median, bars: quartiles)'
set xlabel 'cycles after tune-in'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $time2_shown using ($1+-0.03):2 with linespoints ls 1 title 'ellicast', $time2_shown using ($1+-0.01):5 with linespoints ls 2 title 'draco-whole', $time2_shown using ($1+0.01):8 with linespoints ls 3 title 'draco-fec', $time2_shown using ($1+0.03):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $time2_holes using ($1+-0.03):2:3:4 with yerrorlines ls 1 title 'ellicast', $time2_holes using ($1+-0.01):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time2_holes using ($1+0.01):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time2_holes using ($1+0.03):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $time2_rms using ($1+-0.03):2:3:4 with yerrorlines ls 1 title 'ellicast', $time2_rms using ($1+-0.01):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time2_rms using ($1+0.01):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time2_rms using ($1+0.03):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set output
