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
5 0 0 0.002009 0 0 0 0 0 0 0.8238 0.6495 1.484
10 0 0 0.002009 0 0 100 0 0 0 2.173 1.158 2.753
20 0.002009 0.001507 0.00653 100 100 100 0 0 0 4.786 4.254 5.653
30 0.007033 0.006028 0.01407 100 100 100 0 0 0 9.533 7.844 11.6
50 0.03014 0.02009 0.04019 100 100 100 100 100 100 24.32 21.44 25.63
70 0.1155 0.09042 0.1502 100 100 100 100 100 100 44.37 42.56 47.12
EOD
$loss0_rms << EOD
0 0.01037 0.01037 0.01037 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007756 0.0007756 0.0007756
5 0.01489 0.01433 0.01526 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.1717 0.152 0.2243
10 0.01592 0.01503 0.01658 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.2698 0.1633 0.3157
20 0.01988 0.01909 0.02107 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.4067 0.3648 0.4534
30 0.02368 0.0229 0.02504 NaN NaN NaN 0.0007721 0.0007721 0.0007721 0.6473 0.5537 0.7494
50 0.03436 0.03316 0.0354 NaN NaN NaN NaN NaN NaN 1.21 1.134 1.397
70 0.05499 0.05172 0.05936 NaN NaN NaN NaN NaN NaN 2.361 2.15 2.896
EOD
$time1_shown << EOD
0.25 100 0 0 0 0 0 0 0 0 100 0 0
0.5 100 0 0 0 0 0 95 0 0 100 0 0
1 100 0 0 55 0 0 100 0 0 100 0 0
2 100 0 0 100 0 0 100 0 0 100 0 0
EOD
$time1_holes << EOD
0.25 0.1607 0.1281 0.2708 100 100 100 100 100 100 57.11 56.02 58.78
0.5 0.02914 0.0216 0.05074 100 100 100 0 0 0 17.11 16.43 18.55
1 0 0 0.002009 0 0 100 0 0 0 2.173 1.158 2.753
2 0 0 0 0 0 0 0 0 0 0 0 0
EOD
$time1_rms << EOD
0.25 0.06872 0.06258 0.07259 NaN NaN NaN NaN NaN NaN 7.781 7.406 9.243
0.5 0.03507 0.033 0.03923 NaN NaN NaN 0.0007721 0.0007721 0.0007721 1.512 1.454 1.841
1 0.01592 0.01503 0.01658 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.2698 0.1633 0.3157
2 0.0127 0.01247 0.01307 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007756 0.0007756 0.0007756
EOD
$time2_shown << EOD
0.25 75 0 0 0 0 0 0 0 0 100 0 0
0.5 85 0 0 0 0 0 0 0 0 100 0 0
1 100 0 0 0 0 0 0 0 0 100 0 0
2 100 0 0 5 0 0 100 0 0 100 0 0
EOD
$time2_holes << EOD
0.25 0.7867 0.5481 26.88 100 100 100 100 100 100 72.94 69.97 74.75
0.5 0.1165 0.1015 0.1437 100 100 100 100 100 100 46.65 44.97 50.11
1 0.03014 0.02009 0.04019 100 100 100 100 100 100 24.32 21.44 25.63
2 0.006028 0.002009 0.01055 100 100 100 0 0 0 7.28 6.427 8.396
EOD
$time2_rms << EOD
0.25 0.1105 0.1026 0.122 NaN NaN NaN NaN NaN NaN 9.106 8.492 12.43
0.5 0.0575 0.05597 0.06284 NaN NaN NaN NaN NaN NaN 2.775 2.451 3.184
1 0.03436 0.03316 0.0354 NaN NaN NaN NaN NaN NaN 1.21 1.134 1.397
2 0.0222 0.02167 0.02292 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.0007721 0.4877 0.4386 0.6339
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
