# gnuplot script written by bench_broadcast
set datafile separator ','
set key top left
set grid
set xlabel 'packet loss rate'
set ylabel 'seconds after tune-in'
set title 'ellicast on loopback at 2 Mbit/s: bunny.ply'
set logscale y
plot 'broadcast_summary.csv' every ::1 using 1:3:10:4 with yerrorbars lc rgb '#1f77b4' pt 7 title 'base complete (measured: mean, min..max)',\
     '' every ::1 using 1:8 with lines lc rgb '#1f77b4' dt 2 title 'base (schedule, expected)',\
     '' every ::1 using 1:5 with points lc rgb '#2ca02c' pt 5 title 'base mesh displayed (measured mean)',\
     '' every ::1 using 1:6:11:7 with yerrorbars lc rgb '#d62728' pt 7 title 'full quality (measured: mean, min..max)',\
     '' every ::1 using 1:9 with lines lc rgb '#d62728' dt 2 title 'full quality (schedule, expected)'
