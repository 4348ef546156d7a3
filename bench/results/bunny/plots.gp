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
0 0.004019 0.004019 0.004019 0 0 0 0 0 0 0 0 0
5 0.002009 0.002009 0.004019 0 0 0 0 0 0 0.8238 0.6495 1.484
10 0.006028 0.004019 0.008037 0 0 100 0 0 0 2.173 1.363 2.753
20 0.01708 0.01005 0.02411 100 100 100 0 0 0 4.786 4.285 5.983
30 0.03215 0.02512 0.04421 100 100 100 0 0 0 9.533 7.844 11.8
50 0.2381 0.1939 0.2662 100 100 100 100 100 100 24.74 21.5 25.85
70 1.016 0.9223 1.402 100 100 100 100 100 100 44.89 42.56 47.12
EOD
$loss0_rms << EOD
0 0.0128 0.0128 0.0128 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007756 0.0007756 0.0007756
5 0.02317 0.02238 0.02455 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.1717 0.152 0.2243
10 0.02665 0.02579 0.02795 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.2698 0.1797 0.3157
20 0.03567 0.03353 0.03796 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.4079 0.3648 0.4848
30 0.04428 0.04243 0.04997 NaN NaN NaN 0.0007721 0.0007721 0.0007721 0.6552 0.5537 0.76
50 0.09871 0.0959 0.104 NaN NaN NaN NaN NaN NaN 1.229 1.157 1.397
70 0.1783 0.1737 0.1981 NaN NaN NaN NaN NaN NaN 2.37 2.212 2.896
EOD
$time1_shown << EOD
0.25 90 0 0 0 0 0 0 0 0 100 0 0
0.5 100 0 0 0 0 0 95 0 0 100 0 0
1 100 0 0 55 0 0 100 0 0 100 0 0
2 100 0 0 100 0 0 100 0 0 100 0 0
EOD
$time1_holes << EOD
0.25 1.642 1.449 1.753 100 100 100 100 100 100 57.79 56.91 58.86
0.5 0.3376 0.2783 0.3853 100 100 100 0 0 0 17.56 16.43 19.33
1 0.006028 0.004019 0.008037 0 0 100 0 0 0 2.173 1.363 2.753
2 0.002009 0.002009 0.002512 0 0 0 0 0 0 0 0 0
EOD
$time1_rms << EOD
0.25 0.2073 0.2036 0.2093 NaN NaN NaN NaN NaN NaN 7.842 7.519 9.253
0.5 0.118 0.1106 0.1241 NaN NaN NaN 0.0007721 0.0007721 0.0007721 1.588 1.497 1.851
1 0.02665 0.02579 0.02795 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.2698 0.1797 0.3157
2 0.02108 0.01875 0.02134 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007756 0.0007756 0.0007756
EOD
$time2_shown << EOD
0.25 85 0 0 0 0 0 0 0 0 100 0 0
0.5 100 0 0 0 0 0 0 0 0 100 0 0
1 100 0 0 0 0 0 0 0 0 100 0 0
2 100 0 0 5 0 0 100 0 0 100 0 0
EOD
$time2_holes << EOD
0.25 2.792 2.322 7.287 100 100 100 100 100 100 72.94 70.78 74.82
0.5 1.298 1.213 1.373 100 100 100 100 100 100 47.47 44.97 51.01
1 0.2381 0.1939 0.2662 100 100 100 100 100 100 24.74 21.5 25.85
2 0.02411 0.01557 0.03567 100 100 100 0 0 0 7.388 6.427 8.396
EOD
$time2_rms << EOD
0.25 0.2299 0.2252 0.273 NaN NaN NaN NaN NaN NaN 9.106 8.713 12.43
0.5 0.1964 0.1932 0.201 NaN NaN NaN NaN NaN NaN 2.927 2.481 3.227
1 0.09871 0.0959 0.104 NaN NaN NaN NaN NaN NaN 1.229 1.157 1.397
2 0.04149 0.03675 0.04467 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.4877 0.4468 0.6402
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
