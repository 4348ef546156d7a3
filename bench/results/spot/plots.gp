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
5 100 0 0 100 0 0 100 0 0 100 0 0
10 100 0 0 90 0 0 100 0 0 100 0 0
20 100 0 0 65 0 0 100 0 0 100 0 0
30 95 0 0 60 0 0 80 0 0 100 0 0
50 95 0 0 5 0 0 30 0 0 100 0 0
70 75 0 0 0 0 0 0 0 0 100 0 0
EOD
$loss0_holes << EOD
0 0 0 0 0 0 0 0 0 0 0 0 0
5 0 0 0.00125 0 0 0 0 0 0 0.7059 0 2.294
10 0.002499 0.0007498 0.02549 0 0 0 0 0 0 3.155 1.624 8.34
20 0.0225 0.002749 0.05799 0 0 100 0 0 0 10.12 3.912 15.51
30 0.104 0.003749 0.3139 0 0 100 0 0 0 16.8 13.12 24.15
50 0.4539 0.2524 0.5744 100 100 100 100 0 100 32.66 27.08 35.27
70 4.306 2.27 34.52 100 100 100 100 100 100 50.85 46.1 59.55
EOD
$loss0_rms << EOD
0 0.02021 0.02021 0.02021 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
5 0.03129 0.02142 0.03685 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.171 0.0008228 0.4233
10 0.0412 0.03373 0.04762 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.4644 0.3355 0.9944
20 0.05571 0.04177 0.0736 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 1.174 0.5213 1.894
30 0.08107 0.06029 0.08732 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 1.781 1.474 2.342
50 0.1185 0.09615 0.1238 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 3.314 2.628 3.699
70 0.1958 0.156 0.2444 NaN NaN NaN NaN NaN NaN 4.891 4.263 6.111
EOD
$time1_shown << EOD
0.25 75 0 0 0 0 0 0 0 0 100 0 0
0.5 95 0 0 10 0 0 85 0 0 100 0 0
0.75 100 0 0 60 0 0 95 0 0 100 0 0
1 100 0 0 90 0 0 100 0 0 100 0 0
1.5 100 0 0 95 0 0 100 0 0 100 0 0
2 100 0 0 100 0 0 100 0 0 100 0 0
3 100 0 0 100 0 0 100 0 0 100 0 0
EOD
$time1_holes << EOD
0.25 9.087 5.934 39.12 100 100 100 100 100 100 60.38 57.37 64.4
0.5 0.7823 0.6006 1.115 100 100 100 0 0 0 29.36 24.9 34.98
0.75 0.1315 0.05899 0.174 0 0 100 0 0 0 7.757 5.296 13.9
1 0.002499 0.0007498 0.02549 0 0 0 0 0 0 3.155 1.624 8.34
1.5 0 0 0.002999 0 0 0 0 0 0 0 0 0.06699
2 0 0 0 0 0 0 0 0 0 0 0 0
3 0 0 0 0 0 0 0 0 0 0 0 0
EOD
$time1_rms << EOD
0.25 0.2706 0.2428 0.3144 NaN NaN NaN NaN NaN NaN 10.53 8.82 12.22
0.5 0.1314 0.1233 0.141 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 3.464 2.848 4.404
0.75 0.08356 0.07012 0.08791 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 1.191 0.7363 1.624
1 0.0412 0.03373 0.04762 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.4644 0.3355 0.9944
1.5 0.03026 0.02436 0.03628 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.01472
2 0.02021 0.02021 0.02021 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
3 0.02021 0.02021 0.02021 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
EOD
$time2_shown << EOD
0.25 70 0 0 0 0 0 0 0 0 100 0 0
0.5 90 0 0 0 0 0 15 0 0 100 0 0
0.75 95 0 0 15 0 0 45 0 0 100 0 0
1 95 0 0 60 0 0 80 0 0 100 0 0
1.5 100 0 0 95 0 0 100 0 0 100 0 0
2 100 0 0 100 0 0 100 0 0 100 0 0
3 100 0 0 100 0 0 100 0 0 100 0 0
EOD
$time2_holes << EOD
0.25 13.65 9.463 100 100 100 100 100 100 100 75.39 66.5 80.96
0.5 2.378 1.967 6.667 100 100 100 100 100 100 43.13 33.03 54.08
0.75 0.5964 0.2537 1.081 100 100 100 100 0 100 24.03 17.47 32.06
1 0.104 0.003749 0.3139 0 0 100 0 0 0 16.8 13.12 24.15
1.5 0.03499 0.003999 0.05274 0 0 0 0 0 0 4.992 3.133 7.359
2 0.0004999 0 0.01225 0 0 0 0 0 0 0.2115 0 2.446
3 0 0 0 0 0 0 0 0 0 0 0 0
EOD
$time2_rms << EOD
0.25 0.3294 0.2927 0.3838 NaN NaN NaN NaN NaN NaN 11.62 10.07 14.18
0.5 0.1832 0.1675 0.2166 NaN NaN NaN 0.0008234 0.0008234 0.0008234 4.296 3.132 5.622
0.75 0.1125 0.09852 0.1302 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 2.231 1.689 3.286
1 0.08107 0.06029 0.08732 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 1.781 1.474 2.342
1.5 0.05647 0.04827 0.06676 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.6717 0.4914 0.9717
2 0.03239 0.02702 0.0513 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.03924 0.0008228 0.3923
3 0.02354 0.02021 0.03375 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
EOD
$time3_shown << EOD
0.25 55 0 0 0 0 0 0 0 0 100 0 0
0.5 75 0 0 0 0 0 0 0 0 100 0 0
0.75 85 0 0 0 0 0 0 0 0 100 0 0
1 95 0 0 5 0 0 30 0 0 100 0 0
1.5 100 0 0 40 0 0 90 0 0 100 0 0
2 100 0 0 65 0 0 100 0 0 100 0 0
3 100 0 0 90 0 0 100 0 0 100 0 0
EOD
$time3_holes << EOD
0.25 35.46 17.64 100 100 100 100 100 100 100 78.38 72.61 84.05
0.5 7.289 4.031 38.8 100 100 100 100 100 100 56.02 48.8 62.37
0.75 1.798 1.516 3.026 100 100 100 100 100 100 36.32 32.99 43.82
1 0.4539 0.2524 0.5744 100 100 100 100 0 100 32.66 27.08 35.27
1.5 0.133 0.05474 0.217 100 0 100 0 0 0 15.73 11.07 18.32
2 0.02749 0.007248 0.04374 0 0 100 0 0 0 8.804 6.326 10.02
3 0.002499 0 0.008248 0 0 0 0 0 0 0 0 3.221
EOD
$time3_rms << EOD
0.25 0.437 0.3566 0.5965 NaN NaN NaN NaN NaN NaN 14.34 12.5 19.74
0.5 0.2406 0.1967 0.2827 NaN NaN NaN NaN NaN NaN 6.259 4.525 7.347
0.75 0.1681 0.1503 0.1744 NaN NaN NaN NaN NaN NaN 3.899 3.175 4.248
1 0.1185 0.09615 0.1238 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 3.314 2.628 3.699
1.5 0.08487 0.07349 0.08976 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 1.593 1.161 1.935
2 0.06017 0.05292 0.06604 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.947 0.6803 1.334
3 0.04193 0.03514 0.04795 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.5353
EOD
$loss4_shown << EOD
0 100 0 0 100 0 0 100 0 0 100 0 0
5 100 0 0 100 0 0 100 0 0 100 0 0
10 100 0 0 100 0 0 100 0 0 100 0 0
20 95 0 0 90 0 0 95 0 0 100 0 0
30 95 0 0 80 0 0 80 0 0 100 0 0
50 95 0 0 40 0 0 55 0 0 100 0 0
70 70 0 0 0 0 0 15 0 0 100 0 0
EOD
$loss4_holes << EOD
0 0 0 0 0 0 0 0 0 0 0 0 0
5 0 0 0 0 0 0 0 0 0 0 0 0
10 0 0 0 0 0 0 0 0 0 0 0 0
20 0.0105 0 0.04749 0 0 0 0 0 0 0 0 10.99
30 0.02399 0 0.121 0 0 0 0 0 0 12.6 0 32.96
50 0.5624 0.2137 2.199 100 0 100 0 0 100 33.2 19.53 52.11
70 5.91 2.497 100 100 100 100 100 100 100 53.3 43.17 64
EOD
$loss4_rms << EOD
0 0.02021 0.02021 0.02021 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
5 0.02021 0.02021 0.02021 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
10 0.02021 0.02021 0.02803 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
20 0.04158 0.02021 0.05817 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 1.386
30 0.0498 0.03621 0.07241 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 1.844 0.0008228 4.05
50 0.1115 0.08307 0.1575 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 3.811 2.133 6.356
70 0.2066 0.1544 0.2484 NaN NaN NaN 0.0008234 0.0008234 0.0008234 7.123 4.115 10.22
EOD
$time5_shown << EOD
0.25 95 0 0 0 0 0 0 0 0 100 0 0
0.5 100 0 0 90 0 0 95 0 0 100 0 0
0.75 100 0 0 95 0 0 95 0 0 100 0 0
1 100 0 0 100 0 0 100 0 0 100 0 0
1.5 100 0 0 100 0 0 100 0 0 100 0 0
2 100 0 0 100 0 0 100 0 0 100 0 0
3 100 0 0 100 0 0 100 0 0 100 0 0
EOD
$time5_holes << EOD
0.25 5.375 4.924 6.054 100 100 100 100 100 100 56.47 52.85 66.54
0.5 0.8308 0.5976 0.9468 0 0 0 0 0 0 22.35 15.71 28.41
0.75 0.06399 0.03799 0.108 0 0 0 0 0 0 0 0 0.1765
1 0 0 0 0 0 0 0 0 0 0 0 0
1.5 0 0 0 0 0 0 0 0 0 0 0 0
2 0 0 0 0 0 0 0 0 0 0 0 0
3 0 0 0 0 0 0 0 0 0 0 0 0
EOD
$time5_rms << EOD
0.25 0.2365 0.2319 0.2433 NaN NaN NaN NaN NaN NaN 10.83 8.566 12.37
0.5 0.132 0.1207 0.1421 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 3.071 1.934 4.083
0.75 0.07542 0.06642 0.08046 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.04338
1 0.02021 0.02021 0.02803 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
1.5 0.02021 0.02021 0.02021 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
2 0.02021 0.02021 0.02021 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
3 0.02021 0.02021 0.02021 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
EOD
$time6_shown << EOD
0.25 75 0 0 0 0 0 0 0 0 100 0 0
0.5 95 0 0 55 0 0 60 0 0 100 0 0
0.75 95 0 0 65 0 0 65 0 0 100 0 0
1 95 0 0 80 0 0 80 0 0 100 0 0
1.5 100 0 0 80 0 0 95 0 0 100 0 0
2 100 0 0 95 0 0 100 0 0 100 0 0
3 100 0 0 100 0 0 100 0 0 100 0 0
EOD
$time6_holes << EOD
0.25 5.746 4.648 29.96 100 100 100 100 100 100 66.34 55.07 73.13
0.5 0.9293 0.4574 2.818 0 0 100 0 0 100 39.49 24.6 53.31
0.75 0.181 0.06624 0.3579 0 0 100 0 0 100 19.3 0 33.99
1 0.02399 0 0.121 0 0 0 0 0 0 12.6 0 32.96
1.5 0.002 0 0.1007 0 0 0 0 0 0 3.548 0 18.01
2 0 0 0.007748 0 0 0 0 0 0 0 0 0
3 0 0 0 0 0 0 0 0 0 0 0 0
EOD
$time6_rms << EOD
0.25 0.2365 0.2237 0.2529 NaN NaN NaN NaN NaN NaN 9.547 8.498 14.91
0.5 0.1332 0.1181 0.1864 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 5.224 3.766 7.224
0.75 0.0861 0.07274 0.1078 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 2.486 0.0008228 4.05
1 0.0498 0.03621 0.07241 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 1.844 0.0008228 4.05
1.5 0.03803 0.02194 0.07729 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.704 0.0008228 2.065
2 0.0226 0.02021 0.04847 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
3 0.02021 0.02021 0.02579 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
EOD
$time7_shown << EOD
0.25 60 0 0 0 0 0 0 0 0 100 0 0
0.5 80 0 0 20 0 0 30 0 0 100 0 0
0.75 95 0 0 35 0 0 35 0 0 100 0 0
1 95 0 0 40 0 0 55 0 0 100 0 0
1.5 100 0 0 55 0 0 80 0 0 100 0 0
2 100 0 0 75 0 0 80 0 0 100 0 0
3 100 0 0 100 0 0 100 0 0 100 0 0
EOD
$time7_holes << EOD
0.25 11.26 6.53 100 100 100 100 100 100 100 68.34 66.47 83.15
0.5 3.124 1.429 8.731 100 100 100 100 0 100 52.06 37.32 68.78
0.75 1.093 0.5761 2.852 100 0 100 100 0 100 36.66 21.51 60.24
1 0.5624 0.2137 2.199 100 0 100 0 0 100 33.2 19.53 52.11
1.5 0.4014 0.05224 0.9795 0 0 100 0 0 0 11.44 3.02 29.91
2 0.07598 0.02175 0.3727 0 0 25 0 0 0 3.717 0 12.93
3 0.007498 0 0.03524 0 0 0 0 0 0 0 0 6.341
EOD
$time7_rms << EOD
0.25 0.2811 0.2442 0.3194 NaN NaN NaN NaN NaN NaN 12.85 9.545 16.21
0.5 0.1836 0.1362 0.2131 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 5.864 3.947 10.7
0.75 0.1411 0.1163 0.1731 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 3.96 2.51 9.302
1 0.1115 0.08307 0.1575 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 3.811 2.133 6.356
1.5 0.1026 0.07167 0.1432 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 1.725 0.4887 4.054
2 0.06648 0.04563 0.1048 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.5204 0.0008228 2.063
3 0.04097 0.03132 0.05483 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.9482
EOD
set terminal svg size 1500,480 dynamic font 'Helvetica,13'
set output 'loss_one_cycle_burst0.svg'
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
set output 'loss_one_cycle_burst0.png'
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
set output 'time_loss10_burst0.svg'
set multiplot layout 1,3 title '10% of packets lost, independent loss (median, bars: quartiles)'
set xlabel 'cycles after tune-in'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $time1_shown using ($1+-0.045):2 with linespoints ls 1 title 'ellicast', $time1_shown using ($1+-0.015):5 with linespoints ls 2 title 'draco-whole', $time1_shown using ($1+0.015):8 with linespoints ls 3 title 'draco-fec', $time1_shown using ($1+0.045):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $time1_holes using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time1_holes using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time1_holes using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time1_holes using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $time1_rms using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time1_rms using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time1_rms using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time1_rms using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal pngcairo size 1500,480 font 'Helvetica,11'
set output 'time_loss10_burst0.png'
set multiplot layout 1,3 title '10% of packets lost, independent loss (median, bars: quartiles)'
set xlabel 'cycles after tune-in'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $time1_shown using ($1+-0.045):2 with linespoints ls 1 title 'ellicast', $time1_shown using ($1+-0.015):5 with linespoints ls 2 title 'draco-whole', $time1_shown using ($1+0.015):8 with linespoints ls 3 title 'draco-fec', $time1_shown using ($1+0.045):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $time1_holes using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time1_holes using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time1_holes using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time1_holes using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $time1_rms using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time1_rms using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time1_rms using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time1_rms using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal svg size 1500,480 dynamic font 'Helvetica,13'
set output 'time_loss30_burst0.svg'
set multiplot layout 1,3 title '30% of packets lost, independent loss (median, bars: quartiles)'
set xlabel 'cycles after tune-in'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $time2_shown using ($1+-0.045):2 with linespoints ls 1 title 'ellicast', $time2_shown using ($1+-0.015):5 with linespoints ls 2 title 'draco-whole', $time2_shown using ($1+0.015):8 with linespoints ls 3 title 'draco-fec', $time2_shown using ($1+0.045):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $time2_holes using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time2_holes using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time2_holes using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time2_holes using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $time2_rms using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time2_rms using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time2_rms using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time2_rms using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal pngcairo size 1500,480 font 'Helvetica,11'
set output 'time_loss30_burst0.png'
set multiplot layout 1,3 title '30% of packets lost, independent loss (median, bars: quartiles)'
set xlabel 'cycles after tune-in'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $time2_shown using ($1+-0.045):2 with linespoints ls 1 title 'ellicast', $time2_shown using ($1+-0.015):5 with linespoints ls 2 title 'draco-whole', $time2_shown using ($1+0.015):8 with linespoints ls 3 title 'draco-fec', $time2_shown using ($1+0.045):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $time2_holes using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time2_holes using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time2_holes using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time2_holes using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $time2_rms using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time2_rms using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time2_rms using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time2_rms using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal svg size 1500,480 dynamic font 'Helvetica,13'
set output 'time_loss50_burst0.svg'
set multiplot layout 1,3 title '50% of packets lost, independent loss (median, bars: quartiles)'
set xlabel 'cycles after tune-in'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $time3_shown using ($1+-0.045):2 with linespoints ls 1 title 'ellicast', $time3_shown using ($1+-0.015):5 with linespoints ls 2 title 'draco-whole', $time3_shown using ($1+0.015):8 with linespoints ls 3 title 'draco-fec', $time3_shown using ($1+0.045):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $time3_holes using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time3_holes using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time3_holes using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time3_holes using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $time3_rms using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time3_rms using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time3_rms using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time3_rms using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal pngcairo size 1500,480 font 'Helvetica,11'
set output 'time_loss50_burst0.png'
set multiplot layout 1,3 title '50% of packets lost, independent loss (median, bars: quartiles)'
set xlabel 'cycles after tune-in'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $time3_shown using ($1+-0.045):2 with linespoints ls 1 title 'ellicast', $time3_shown using ($1+-0.015):5 with linespoints ls 2 title 'draco-whole', $time3_shown using ($1+0.015):8 with linespoints ls 3 title 'draco-fec', $time3_shown using ($1+0.045):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $time3_holes using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time3_holes using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time3_holes using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time3_holes using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $time3_rms using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time3_rms using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time3_rms using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time3_rms using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal svg size 1500,480 dynamic font 'Helvetica,13'
set output 'loss_one_cycle_burst8.svg'
set multiplot layout 1,3 title 'After one cycle, bursty loss (Gilbert, mean burst 8 packets) (median, bars: quartiles)'
set xlabel 'packets lost (%)'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $loss4_shown using ($1+-0.75):2 with linespoints ls 1 title 'ellicast', $loss4_shown using ($1+-0.25):5 with linespoints ls 2 title 'draco-whole', $loss4_shown using ($1+0.25):8 with linespoints ls 3 title 'draco-fec', $loss4_shown using ($1+0.75):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $loss4_holes using ($1+-0.75):2:3:4 with yerrorlines ls 1 title 'ellicast', $loss4_holes using ($1+-0.25):5:6:7 with yerrorlines ls 2 title 'draco-whole', $loss4_holes using ($1+0.25):8:9:10 with yerrorlines ls 3 title 'draco-fec', $loss4_holes using ($1+0.75):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $loss4_rms using ($1+-0.75):2:3:4 with yerrorlines ls 1 title 'ellicast', $loss4_rms using ($1+-0.25):5:6:7 with yerrorlines ls 2 title 'draco-whole', $loss4_rms using ($1+0.25):8:9:10 with yerrorlines ls 3 title 'draco-fec', $loss4_rms using ($1+0.75):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal pngcairo size 1500,480 font 'Helvetica,11'
set output 'loss_one_cycle_burst8.png'
set multiplot layout 1,3 title 'After one cycle, bursty loss (Gilbert, mean burst 8 packets) (median, bars: quartiles)'
set xlabel 'packets lost (%)'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $loss4_shown using ($1+-0.75):2 with linespoints ls 1 title 'ellicast', $loss4_shown using ($1+-0.25):5 with linespoints ls 2 title 'draco-whole', $loss4_shown using ($1+0.25):8 with linespoints ls 3 title 'draco-fec', $loss4_shown using ($1+0.75):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $loss4_holes using ($1+-0.75):2:3:4 with yerrorlines ls 1 title 'ellicast', $loss4_holes using ($1+-0.25):5:6:7 with yerrorlines ls 2 title 'draco-whole', $loss4_holes using ($1+0.25):8:9:10 with yerrorlines ls 3 title 'draco-fec', $loss4_holes using ($1+0.75):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $loss4_rms using ($1+-0.75):2:3:4 with yerrorlines ls 1 title 'ellicast', $loss4_rms using ($1+-0.25):5:6:7 with yerrorlines ls 2 title 'draco-whole', $loss4_rms using ($1+0.25):8:9:10 with yerrorlines ls 3 title 'draco-fec', $loss4_rms using ($1+0.75):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal svg size 1500,480 dynamic font 'Helvetica,13'
set output 'time_loss10_burst8.svg'
set multiplot layout 1,3 title '10% of packets lost, bursty loss (Gilbert, mean burst 8 packets) (median, bars: quartiles)'
set xlabel 'cycles after tune-in'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $time5_shown using ($1+-0.045):2 with linespoints ls 1 title 'ellicast', $time5_shown using ($1+-0.015):5 with linespoints ls 2 title 'draco-whole', $time5_shown using ($1+0.015):8 with linespoints ls 3 title 'draco-fec', $time5_shown using ($1+0.045):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $time5_holes using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time5_holes using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time5_holes using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time5_holes using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $time5_rms using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time5_rms using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time5_rms using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time5_rms using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal pngcairo size 1500,480 font 'Helvetica,11'
set output 'time_loss10_burst8.png'
set multiplot layout 1,3 title '10% of packets lost, bursty loss (Gilbert, mean burst 8 packets) (median, bars: quartiles)'
set xlabel 'cycles after tune-in'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $time5_shown using ($1+-0.045):2 with linespoints ls 1 title 'ellicast', $time5_shown using ($1+-0.015):5 with linespoints ls 2 title 'draco-whole', $time5_shown using ($1+0.015):8 with linespoints ls 3 title 'draco-fec', $time5_shown using ($1+0.045):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $time5_holes using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time5_holes using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time5_holes using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time5_holes using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $time5_rms using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time5_rms using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time5_rms using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time5_rms using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal svg size 1500,480 dynamic font 'Helvetica,13'
set output 'time_loss30_burst8.svg'
set multiplot layout 1,3 title '30% of packets lost, bursty loss (Gilbert, mean burst 8 packets) (median, bars: quartiles)'
set xlabel 'cycles after tune-in'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $time6_shown using ($1+-0.045):2 with linespoints ls 1 title 'ellicast', $time6_shown using ($1+-0.015):5 with linespoints ls 2 title 'draco-whole', $time6_shown using ($1+0.015):8 with linespoints ls 3 title 'draco-fec', $time6_shown using ($1+0.045):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $time6_holes using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time6_holes using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time6_holes using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time6_holes using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $time6_rms using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time6_rms using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time6_rms using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time6_rms using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal pngcairo size 1500,480 font 'Helvetica,11'
set output 'time_loss30_burst8.png'
set multiplot layout 1,3 title '30% of packets lost, bursty loss (Gilbert, mean burst 8 packets) (median, bars: quartiles)'
set xlabel 'cycles after tune-in'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $time6_shown using ($1+-0.045):2 with linespoints ls 1 title 'ellicast', $time6_shown using ($1+-0.015):5 with linespoints ls 2 title 'draco-whole', $time6_shown using ($1+0.015):8 with linespoints ls 3 title 'draco-fec', $time6_shown using ($1+0.045):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $time6_holes using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time6_holes using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time6_holes using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time6_holes using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $time6_rms using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time6_rms using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time6_rms using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time6_rms using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal svg size 1500,480 dynamic font 'Helvetica,13'
set output 'time_loss50_burst8.svg'
set multiplot layout 1,3 title '50% of packets lost, bursty loss (Gilbert, mean burst 8 packets) (median, bars: quartiles)'
set xlabel 'cycles after tune-in'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $time7_shown using ($1+-0.045):2 with linespoints ls 1 title 'ellicast', $time7_shown using ($1+-0.015):5 with linespoints ls 2 title 'draco-whole', $time7_shown using ($1+0.015):8 with linespoints ls 3 title 'draco-fec', $time7_shown using ($1+0.045):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $time7_holes using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time7_holes using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time7_holes using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time7_holes using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $time7_rms using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time7_rms using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time7_rms using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time7_rms using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set terminal pngcairo size 1500,480 font 'Helvetica,11'
set output 'time_loss50_burst8.png'
set multiplot layout 1,3 title '50% of packets lost, bursty loss (Gilbert, mean burst 8 packets) (median, bars: quartiles)'
set xlabel 'cycles after tune-in'
unset logscale y
set yrange [0:105]
set ylabel 'trials showing anything (%)'
plot $time7_shown using ($1+-0.045):2 with linespoints ls 1 title 'ellicast', $time7_shown using ($1+-0.015):5 with linespoints ls 2 title 'draco-whole', $time7_shown using ($1+0.015):8 with linespoints ls 3 title 'draco-fec', $time7_shown using ($1+0.045):11 with linespoints ls 4 title 'draco-clusters'
set ylabel 'original surface missing (%)'
plot $time7_holes using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time7_holes using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time7_holes using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time7_holes using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
set yrange [*:*]
set logscale y
set ylabel 'RMS distance (% of bbox diagonal, shown trials)'
plot $time7_rms using ($1+-0.045):2:3:4 with yerrorlines ls 1 title 'ellicast', $time7_rms using ($1+-0.015):5:6:7 with yerrorlines ls 2 title 'draco-whole', $time7_rms using ($1+0.015):8:9:10 with yerrorlines ls 3 title 'draco-fec', $time7_rms using ($1+0.045):11:12:13 with yerrorlines ls 4 title 'draco-clusters'
unset logscale y
unset multiplot
set output
