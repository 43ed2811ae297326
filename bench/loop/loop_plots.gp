# Plots of the servo-loop benchmark, run by bench/loop/loop_report.sh:
#   gnuplot -e "dir='bench/results'; runs='echo box_pair ...'; loop_runs='box_pair ...'" \
#           bench/loop/loop_plots.gp          (loop_runs: the runs with a servo loop, not the echo)
# Reads dir/loop_distributions.csv (run,metric,fraction,value_us) and
# dir/loop_latency.csv; writes three PNGs into dir.
set datafile separator ","
set terminal pngcairo size 1100,700 noenhanced font ",10"
set key outside right top
set grid
# Rows of one run and metric: "fraction,value" (value floored at 0.1 us for log x).
sel(r, m) = sprintf("< awk -F, '$1 == \"%s\" && $2 == \"%s\" { v = $4 < 0.1 ? 0.1 : $4; print $3 \",\" v }' %s/loop_distributions.csv", r, m, dir)

set output dir."/loop_rtt_cdf.png"
set title "Pose-to-wrench round trip over LCM (udpm, loopback): CDF per run"
set logscale x
set xlabel "round trip (us), log scale"
set ylabel "fraction of answered poses <= x"
set yrange [0:1]
# Colours repeat after 8 runs: dashed from the 9th on.
dashed_after_8(i) = i > 8 ? 2 : 1
plot for [i = 1:words(runs)] sel(word(runs, i), "rtt") using 2:1 with lines \
     lc i dt dashed_after_8(i) lw (word(runs, i) eq "echo" ? 3 : 1.5) title word(runs, i)

set output dir."/loop_jitter_cdf.png"
set title "Servo period jitter |period - 1000 us|: CDF per run (ticks of the replay window)"
set xlabel "period jitter (us), log scale (0 shown at 0.1)"
set ylabel "fraction of ticks <= x"
plot for [i = 1:words(loop_runs)] sel(word(loop_runs, i), "jitter") using 2:1 with lines \
     lc i dt dashed_after_8(i) lw 1.5 title word(loop_runs, i)

set output dir."/loop_compute_vs_size.png"
set title "Per-tick compute (PD + dynamics + publish) against scene size (meshes only)"
set xlabel "scene triangles (objects), log scale"
set ylabel "compute per tick (us), log scale"
set logscale xy
set xrange [10:1e6]
set yrange [10:3000]
set key inside left top
# Columns of loop_latency.csv: 3 scene_triangles, 17 p50, 18 p99, 19 p99.9, 1 run.
ok(x) = (x eq "-" || x eq "" || x + 0 <= 0) ? NaN : x + 0
plot dir."/loop_latency.csv" using (ok(strcol(3))):(ok(strcol(18))) every ::1 with points pt 7 ps 1.5 title "p99", \
     "" using (ok(strcol(3))):(ok(strcol(17))) every ::1 with points pt 5 ps 1.2 title "p50", \
     "" using (ok(strcol(3))):(ok(strcol(19))) every ::1 with points pt 9 ps 1.2 title "p99.9", \
     "" using (ok(strcol(3))):(ok(strcol(18))):1 every ::1 with labels offset 0,1 font ",8" notitle, \
     1000 with lines dt 2 lc rgb "red" title "1 ms period"
