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
5 100 0 0 90 0 0 100 0 0 100 0 0
10 95 0 0 60 0 0 100 0 0 100 0 0
20 100 0 0 35 0 0 65 0 0 100 0 0
30 85 0 0 15 0 0 35 0 0 100 0 0
50 80 0 0 0 0 0 0 0 0 100 0 0
70 65 0 0 0 0 0 0 0 0 100 0 0
EOD
$loss0_holes << EOD
0 0 0 0 0 0 0 0 0 0 0 0 0
5 1.359 0 1.409 0 0 0 0 0 0 2.337 0.5294 6.077
10 1.429 1.379 1.517 0 0 100 0 0 0 7.757 5.296 13.9
20 1.52 1.437 1.645 100 0 100 0 0 100 12.28 8.108 16.22
30 1.684 1.607 1.779 100 100 100 100 0 100 24.03 17.47 32.06
50 2.053 1.934 5.782 100 100 100 100 100 100 36.32 32.99 43.82
70 4.46 2.16 100 100 100 100 100 100 100 59.71 49.68 69.47
EOD
$loss0_rms << EOD
0 0.01718 0.01718 0.01718 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
5 0.2076 0.01718 0.2087 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.412 0.1285 0.9472
10 0.2089 0.2077 0.2106 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 1.191 0.7363 1.624
20 0.2108 0.2093 0.2142 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 1.329 0.9033 1.894
30 0.2141 0.2124 0.2154 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 2.231 1.689 3.286
50 0.2209 0.2194 0.2346 NaN NaN NaN NaN NaN NaN 3.899 3.175 4.248
70 0.2257 0.2231 0.2288 NaN NaN NaN NaN NaN NaN 6.172 4.613 7.604
EOD
$time1_shown << EOD
0.25 55 0 0 0 0 0 0 0 0 100 0 0
0.5 90 0 0 0 0 0 0 0 0 100 0 0
0.75 90 0 0 20 0 0 80 0 0 100 0 0
1 95 0 0 60 0 0 100 0 0 100 0 0
1.5 100 0 0 95 0 0 100 0 0 100 0 0
2 100 0 0 95 0 0 100 0 0 100 0 0
3 100 0 0 100 0 0 100 0 0 100 0 0
EOD
$time1_holes << EOD
0.25 7.398 2.392 100 100 100 100 100 100 100 69.76 65.54 75.41
0.5 2.102 2.013 5.959 100 100 100 100 100 100 43.15 34.9 54.82
0.75 1.762 1.719 1.812 100 100 100 0 0 0 22.3 17.82 26.95
1 1.429 1.379 1.517 0 0 100 0 0 0 7.757 5.296 13.9
1.5 1.374 1.354 1.427 0 0 0 0 0 0 2.261 0 4.585
2 0 0 1.329 0 0 0 0 0 0 0 0 0.06699
3 0 0 0 0 0 0 0 0 0 0 0 0
EOD
$time1_rms << EOD
0.25 0.2282 0.228 0.2626 NaN NaN NaN NaN NaN NaN 13.45 11.4 14.01
0.5 0.2223 0.2214 0.2238 NaN NaN NaN NaN NaN NaN 6.186 4.331 7.748
0.75 0.2161 0.2153 0.2167 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 2.606 2.163 3.404
1 0.2089 0.2077 0.2106 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 1.191 0.7363 1.624
1.5 0.2078 0.2075 0.2088 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.3739 0.0008228 0.595
2 0.01718 0.01718 0.2071 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.01472
3 0.01718 0.01718 0.01718 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
EOD
$time2_shown << EOD
0.25 50 0 0 0 0 0 0 0 0 100 0 0
0.5 75 0 0 0 0 0 0 0 0 100 0 0
0.75 80 0 0 5 0 0 20 0 0 100 0 0
1 85 0 0 15 0 0 35 0 0 100 0 0
1.5 95 0 0 70 0 0 90 0 0 100 0 0
2 100 0 0 95 0 0 100 0 0 100 0 0
3 100 0 0 100 0 0 100 0 0 100 0 0
EOD
$time2_holes << EOD
0.25 53.74 2.554 100 100 100 100 100 100 100 78.56 74.01 86.59
0.5 2.32 2.146 29.98 100 100 100 100 100 100 58.11 45.1 67.28
0.75 1.972 1.896 2.943 100 100 100 100 100 100 36.9 28.71 46.28
1 1.684 1.607 1.779 100 100 100 100 0 100 24.03 17.47 32.06
1.5 1.526 1.458 1.626 0 0 100 0 0 0 13.98 7.614 21.11
2 1.373 1.364 1.47 0 0 0 0 0 0 4.992 3.133 7.359
3 0 0 1.361 0 0 0 0 0 0 0 0 2.054
EOD
$time2_rms << EOD
0.25 0.2302 0.2296 0.2325 NaN NaN NaN NaN NaN NaN 14.09 10.35 22.16
0.5 0.2249 0.223 0.2267 NaN NaN NaN NaN NaN NaN 7.263 5.738 8.602
0.75 0.2201 0.2188 0.2213 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 3.784 2.476 4.785
1 0.2141 0.2124 0.2154 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 2.231 1.689 3.286
1.5 0.2112 0.2096 0.2131 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 1.556 0.9604 2.164
2 0.2083 0.2076 0.2098 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.6717 0.4914 0.9717
3 0.01718 0.01718 0.2077 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.353
EOD
$time3_shown << EOD
0.25 25 0 0 0 0 0 0 0 0 100 0 0
0.5 55 0 0 0 0 0 0 0 0 100 0 0
0.75 65 0 0 0 0 0 0 0 0 100 0 0
1 80 0 0 0 0 0 0 0 0 100 0 0
1.5 90 0 0 10 0 0 30 0 0 100 0 0
2 100 0 0 40 0 0 75 0 0 100 0 0
3 100 0 0 75 0 0 100 0 0 100 0 0
EOD
$time3_holes << EOD
0.25 100 77 100 100 100 100 100 100 100 83.82 78.16 86.5
0.5 7.202 2.553 100 100 100 100 100 100 100 68.3 62.15 73.24
0.75 6.034 2.178 100 100 100 100 100 100 100 49.55 43.29 57.58
1 2.053 1.934 5.782 100 100 100 100 100 100 36.32 32.99 43.82
1.5 1.817 1.658 1.916 100 100 100 100 0 100 26.08 22.19 30.78
2 1.649 1.551 1.674 100 0 100 0 0 25 15.73 11.07 18.32
3 1.48 1.377 1.522 0 0 25 0 0 0 6.298 3.773 9.297
EOD
$time3_rms << EOD
0.25 0.2965 0.2315 0.2997 NaN NaN NaN NaN NaN NaN 15.27 13.86 20.15
0.5 0.2306 0.2284 0.2883 NaN NaN NaN NaN NaN NaN 10.13 8.352 11.78
0.75 0.2265 0.224 0.2801 NaN NaN NaN NaN NaN NaN 5.232 4.033 6.259
1 0.2209 0.2194 0.2346 NaN NaN NaN NaN NaN NaN 3.899 3.175 4.248
1.5 0.2165 0.2143 0.2185 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 2.426 1.816 3.257
2 0.2134 0.2117 0.2148 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 1.593 1.161 1.935
3 0.2103 0.2076 0.2111 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.7265 0.5294 0.9501
EOD
$loss4_shown << EOD
0 100 0 0 100 0 0 100 0 0 100 0 0
5 100 0 0 95 0 0 95 0 0 100 0 0
10 100 0 0 95 0 0 95 0 0 100 0 0
20 95 0 0 80 0 0 75 0 0 100 0 0
30 95 0 0 65 0 0 55 0 0 100 0 0
50 75 0 0 35 0 0 35 0 0 100 0 0
70 60 0 0 0 0 0 5 0 0 100 0 0
EOD
$loss4_holes << EOD
0 0 0 0 0 0 0 0 0 0 0 0 0
5 0 0 0 0 0 0 0 0 0 0 0 0
10 0 0 1.389 0 0 0 0 0 0 0 0 0.1765
20 1.371 0 1.761 0 0 0 0 0 25 1.019 0 19.61
30 1.506 0.9913 1.709 0 0 100 0 0 100 19.3 0 33.99
50 2.032 1.652 26.88 100 0 100 100 0 100 36.66 21.51 60.24
70 4.1 2.168 100 100 100 100 100 100 100 60.49 54.59 67.81
EOD
$loss4_rms << EOD
0 0.01718 0.01718 0.01718 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
5 0.01718 0.01718 0.01718 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
10 0.01718 0.01718 0.2084 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.04338
20 0.2076 0.01718 0.2156 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.1717 0.0008228 2.438
30 0.2098 0.1121 0.2149 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 2.486 0.0008228 4.05
50 0.2167 0.2118 0.2228 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 3.96 2.51 9.302
70 0.2244 0.2205 0.226 NaN NaN NaN 0.0008234 0.0008234 0.0008234 9.291 5.855 12.1
EOD
$time5_shown << EOD
0.25 50 0 0 0 0 0 0 0 0 100 0 0
0.5 100 0 0 0 0 0 0 0 0 100 0 0
0.75 100 0 0 95 0 0 95 0 0 100 0 0
1 100 0 0 95 0 0 95 0 0 100 0 0
1.5 100 0 0 100 0 0 100 0 0 100 0 0
2 100 0 0 100 0 0 100 0 0 100 0 0
3 100 0 0 100 0 0 100 0 0 100 0 0
EOD
$time5_holes << EOD
0.25 53.67 2.393 100 100 100 100 100 100 100 69.51 64.38 74.31
0.5 1.968 1.939 2.002 100 100 100 100 100 100 42.72 33.24 46.19
0.75 1.649 1.57 1.698 0 0 0 0 0 0 14.83 10.46 19.33
1 0 0 1.389 0 0 0 0 0 0 0 0 0.1765
1.5 0 0 0.3524 0 0 0 0 0 0 0 0 0
2 0 0 0 0 0 0 0 0 0 0 0 0
3 0 0 0 0 0 0 0 0 0 0 0 0
EOD
$time5_rms << EOD
0.25 0.228 0.228 0.2284 NaN NaN NaN NaN NaN NaN 13.12 10.14 13.95
0.5 0.2203 0.2197 0.2208 NaN NaN NaN NaN NaN NaN 6.371 4.205 7.406
0.75 0.2137 0.2123 0.2149 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 2.033 1.313 2.591
1 0.01718 0.01718 0.2084 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.04338
1.5 0.01718 0.01718 0.06506 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
2 0.01718 0.01718 0.01718 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
3 0.01718 0.01718 0.01718 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
EOD
$time6_shown << EOD
0.25 50 0 0 0 0 0 0 0 0 100 0 0
0.5 85 0 0 0 0 0 0 0 0 100 0 0
0.75 85 0 0 55 0 0 45 0 0 100 0 0
1 95 0 0 65 0 0 55 0 0 100 0 0
1.5 95 0 0 80 0 0 75 0 0 100 0 0
2 100 0 0 80 0 0 95 0 0 100 0 0
3 100 0 0 100 0 0 100 0 0 100 0 0
EOD
$time6_holes << EOD
0.25 53.54 2.493 100 100 100 100 100 100 100 73.46 65.18 84.02
0.5 2.029 1.978 2.272 100 100 100 100 100 100 47.27 44 58.01
0.75 1.82 1.649 2.113 0 0 100 100 0 100 33.54 16.88 46.13
1 1.506 0.9913 1.709 0 0 100 0 0 100 19.3 0 33.99
1.5 1.436 0 1.683 0 0 0 0 0 25 12.25 0 25.95
2 1.364 0 1.534 0 0 0 0 0 0 3.548 0 18.01
3 0 0 0 0 0 0 0 0 0 0 0 0
EOD
$time6_rms << EOD
0.25 0.229 0.228 0.278 NaN NaN NaN NaN NaN NaN 12.39 10.02 20.13
0.5 0.2208 0.2206 0.2232 NaN NaN NaN NaN NaN NaN 7.432 6.193 9.014
0.75 0.2159 0.2138 0.2205 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 3.769 2.705 5.547
1 0.2098 0.1121 0.2149 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 2.486 0.0008228 4.05
1.5 0.2097 0.01718 0.214 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 1.844 0.0008228 3.703
2 0.208 0.01718 0.2117 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.704 0.0008228 2.065
3 0.01718 0.01718 0.01718 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008228 0.0008228 0.0008228
EOD
$time7_shown << EOD
0.25 30 0 0 0 0 0 0 0 0 100 0 0
0.5 50 0 0 0 0 0 0 0 0 100 0 0
0.75 60 0 0 20 0 0 30 0 0 100 0 0
1 75 0 0 35 0 0 35 0 0 100 0 0
1.5 85 0 0 40 0 0 50 0 0 100 0 0
2 95 0 0 55 0 0 55 0 0 100 0 0
3 100 0 0 80 0 0 80 0 0 100 0 0
EOD
$time7_holes << EOD
0.25 100 5.866 100 100 100 100 100 100 100 76.95 68.39 86.58
0.5 51.19 2.131 100 100 100 100 100 100 100 59.18 46.92 74.23
0.75 2.328 2.023 100 100 100 100 100 0 100 48.09 33.4 68.78
1 2.032 1.652 26.88 100 0 100 100 0 100 36.66 21.51 60.24
1.5 1.858 1.523 2.1 100 0 100 50 0 100 29.06 12.68 44.7
2 1.619 1.385 1.819 0 0 100 0 0 100 11.44 3.02 29.91
3 1.385 0 1.553 0 0 0 0 0 0 1.641 0 9.904
EOD
$time7_rms << EOD
0.25 0.2289 0.228 0.2317 NaN NaN NaN NaN NaN NaN 13.81 11.66 20.16
0.5 0.2229 0.2207 0.224 NaN NaN NaN NaN NaN NaN 9.474 6.544 12.63
0.75 0.2223 0.2171 0.2244 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 5.475 3.299 10.7
1 0.2167 0.2118 0.2228 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 3.96 2.51 9.302
1.5 0.2151 0.2102 0.221 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 3.507 1.65 5.463
2 0.2132 0.2078 0.2158 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 1.725 0.4887 4.054
3 0.2078 0.01718 0.2121 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.0008234 0.2548 0.0008228 1.651
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
