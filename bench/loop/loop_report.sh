#!/usr/bin/env bash
# Report step of the servo-loop benchmark (bench/run_loop_bench.sh runs it):
#
#   bench/loop/loop_report.sh WORK_DIR OUT_DIR
#
# Reads each run's files in WORK_DIR/<run>/ (ticks.csv from haptic_server
# --timing-log, result.csv and summary.json from probe_replay, cpu.txt from
# loop_cpu.sh, server.err, run.txt) and writes to OUT_DIR:
#   loop_latency.md             the report
#   loop_latency.csv            one row per run
#   loop_distributions.csv      quantiles of round trip, period jitter and
#                               compute time per run (what the plots draw)
#   loop_rtt_cdf.png, loop_jitter_cdf.png, loop_compute_vs_size.png
#                               (bench/loop/loop_plots.gp, gnuplot)
# Tick statistics cover the replay: the ticks from the first to the last one
# that rendered a new pose (the flag kFlagStaleInput, 16, clear), so start-up
# and shut-down idling are left out. Percentiles are nearest-rank.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
(($# == 2)) || { echo "usage: loop_report.sh WORK_DIR OUT_DIR" >&2; exit 2; }
WORK="$1" OUT="$2"
[[ -s "$WORK/runs.txt" ]] || { echo "loop_report: $WORK/runs.txt missing or empty: nothing was run" >&2; exit 1; }
mkdir -p "$OUT"
meta() { sed -n "s/^$1=//p" "$WORK/meta.txt" | tail -1; }
kv() { sed -n "s/.*\b$2=\([^ ]*\).*/\1/p" "$1" 2>/dev/null | tail -1; }  # FILE KEY
mapfile -t RUNS < "$WORK/runs.txt"

# Nearest-rank quantiles of the numbers on stdin: prints "p50 p99 p99.9 max".
quantiles() {
  sort -g | awk '{ v[NR] = $1 } END {
    if (NR == 0) { print "- - - -"; exit }
    n = split("0.5 0.99 0.999", p, " ")
    for (i = 1; i <= n; i++) { r = int(p[i] * NR); if (r < p[i] * NR) r++; if (r < 1) r = 1; printf "%.1f ", v[r] }
    printf "%.1f\n", v[NR] }'
}
# Quantile points of the numbers on stdin for the CDF plots: "fraction,value".
cdf_points() {
  sort -g | awk '{ v[NR] = $1 } END {
    if (NR == 0) exit
    m = split("0.001 0.005", f, " ")
    for (i = 1; i <= 99; i++) f[++m] = i / 100
    m2 = split("0.995 0.999 0.9995 0.9999 1", g, " "); for (i = 1; i <= m2; i++) f[++m] = g[i]
    for (i = 1; i <= m; i++) { r = int(f[i] * NR); if (r < f[i] * NR) r++; if (r < 1) r = 1; printf "%s,%s\n", f[i], v[r] } }'
}

# The replay window of a tick log: prints "period_us compute_us contact missed" rows.
tick_window() {
  awk -F, '/^#/ || $1 == "tick" { next }
    { n++; p[n] = $2; c[n] = $3; k[n] = $4; m[n] = $6; if (int($5 / 16) % 2 == 0) { if (!first) first = n; last = n } }
    END { for (i = first + 1; first && i <= last; i++) print p[i], c[i], k[i], m[i] }' "$1"
}

csv="$OUT/loop_latency.csv"
dist="$OUT/loop_distributions.csv"
echo "run,config,scene_triangles,tool_triangles,exit,load1_before,load1_after,ticks,rate_hz,jitter_p50_us,jitter_p99_us,jitter_p999_us,jitter_max_us,misses,misses_per_min,server_misses_whole_run,compute_p50_us,compute_p99_us,compute_p999_us,compute_max_us,contact_fraction,poses_sent,answered,superseded,lost,rtt_p50_us,rtt_p99_us,rtt_max_us,rtt_p50_over_echo,server_cpu_pct,replay_cpu_pct,max_force_N,misses_compute_over_period" > "$csv"
echo "run,metric,fraction,value_us" > "$dist"

echo_p50=""
[[ -f "$WORK/echo/summary.json" ]] && echo_p50=$(jq -r '.latency_us.p50' "$WORK/echo/summary.json")
nominal_us=1000
for run in "${RUNS[@]}"; do
  d="$WORK/$run"
  config=$(kv "$d/run.txt" config); rc=$(kv "$d/run.txt" exit)
  lb=$(sed -n 's/^load_before=\([^ ]*\).*/\1/p' "$d/run.txt"); la=$(sed -n 's/^load_after=\([^ ]*\).*/\1/p' "$d/run.txt")
  tris=$(sed -n 's/.*triangles: tool \([0-9]*\), scene objects \([0-9]*\).*/\2 \1/p' "$d/server.err" 2>/dev/null | tail -1)
  read -r scene_tris tool_tris <<< "${tris:-- -}"
  ticks=- rate=- j50=- j99=- j999=- jmax=- misses=- mpm=- c50=- c99=- c999=- cmax=- contact=- smiss=- mcomp=-
  if [[ -s "$d/ticks.csv" ]]; then
    tick_window "$d/ticks.csv" > "$d/window.txt"
    read -r ticks rate misses mpm contact mcomp < <(awk -v nom="$nominal_us" '
      { n++; t += $1; k += ($3 > 0); m += $4; mc += ($4 && $2 > nom) }
      END { if (!n || t <= 0) { print "0 - - - - -"; exit }
            printf "%d %.1f %d %.1f %.3f %d\n", n, n / t * 1e6, m, m / (t * 1e-6 / 60), k / n, mc }' "$d/window.txt")
    read -r j50 j99 j999 jmax < <(awk -v nom="$nominal_us" '{ x = $1 - nom; print (x < 0 ? -x : x) }' "$d/window.txt" | quantiles)
    read -r c50 c99 c999 cmax < <(awk '{ print $2 }' "$d/window.txt" | quantiles)
    awk -v nom="$nominal_us" '{ x = $1 - nom; print (x < 0 ? -x : x) }' "$d/window.txt" | cdf_points | sed "s/^/$run,jitter,/" >> "$dist"
    awk '{ print $2 }' "$d/window.txt" | cdf_points | sed "s/^/$run,compute,/" >> "$dist"
    smiss=$(sed -n 's/.*deadline_misses=\([0-9]*\).*/\1/p' "$d/server.out" | tail -1)
  fi
  sent=- answered=- superseded=- lost=- r50=- r99=- rmax=- ratio=- force=-
  if [[ -s "$d/summary.json" ]]; then
    read -r sent answered superseded lost r50 r99 rmax force < <(jq -r '[.poses_sent, .answered, .superseded, .lost,
      .latency_us.p50, .latency_us.p99, .latency_us.max, (.max_force_N * 1000 | round / 1000)] | @tsv' "$d/summary.json")
    [[ -n "$echo_p50" && "$echo_p50" != 0 ]] && ratio=$(awk -v a="$r50" -v b="$echo_p50" 'BEGIN { printf "%.2f", a / b }')
  fi
  if [[ -s "$d/result.csv" ]]; then
    awk -F, 'NR > 1 && $11 == 1 && $22 != "" { print $22 }' "$d/result.csv" | cdf_points | sed "s/^/$run,rtt,/" >> "$dist"
  fi
  scpu=- rcpu=-
  if [[ -s "$d/cpu.txt" ]]; then
    read -r scpu rcpu < <(awk '{ for (i = 1; i <= NF; i++) { split($i, kv, "="); v[kv[1]] = kv[2] } }
      END { w = v["wall_s"]; s = v["server_cpu_s"]
            printf "%s %.1f\n", ((s == "nan" || w <= 0) ? "-" : sprintf("%.1f", 100 * s / w)), (w > 0 ? 100 * v["replay_cpu_s"] / w : 0) }' "$d/cpu.txt")
  fi
  echo "$run,$config,$scene_tris,$tool_tris,$rc,$lb,$la,$ticks,$rate,$j50,$j99,$j999,$jmax,$misses,$mpm,$smiss,$c50,$c99,$c999,$cmax,$contact,$sent,$answered,$superseded,$lost,$r50,$r99,$rmax,$ratio,$scpu,$rcpu,$force,$mcomp" >> "$csv"
done

# Misses by cause against the platform's floor, the geometry thread and the
# force difference it makes (issue 11): one row per run in loop_floor.csv.
floor="$OUT/loop_floor.csv"
echo "run,misses,misses_compute,misses_late_wakeup,late_wakeups,late_wakeups_per_min,cyclictest_cycles,cyclictest_late_1ms,cyclictest_late_per_min,cyclictest_max_us,wake_latency_p99_us,compute_p50_us,geometry_thread,pd_update_rate_hz,model_age_p50,model_age_p99,model_age_max,pose_triggered,rtt_p50_us,rtt_target_us,force_diff_rms_N,force_diff_max_N,misses_stalled,tick_cpu_p99_us,tick_cpu_max_us,probe_chunks,probe_cpu_stalls,probe_max_cpu_us,misses_charged" > "$floor"
for run in "${RUNS[@]}"; do
  d="$WORK/$run"
  s_out="$d/server.out"
  sv() { local v; v=$(kv "$s_out" "$1"); echo "${v:--}"; }
  ctc=- ctl=- ctm=- ctmax=- lpm=-
  if [[ -s "$d/cyclictest.txt" ]]; then
    read -r ctc ctl ctmax < <(awk '/^# Total:/ { c = $3 } /^# Max Latencies:/ { m = $4 + 0 } /^# Histogram Overflows:/ { o = $4 + 0 }
      !/^#/ && NF >= 2 && $1 + 0 >= 1000 { l += $2 } END { printf "%d %d %d\n", c, l + o, m }' "$d/cyclictest.txt")
    ctm=$(awk -v c="$ctc" -v l="$ctl" 'BEGIN { printf "%.1f", (c > 0 ? l / (c / 60000) : 0) }')
  fi
  pch=- pst=- pmax=-
  if [[ -s "$d/cpu_stall_probe.txt" ]]; then
    pv() { sed -n "s/.*[[:space:]]$1=\([^ ]*\).*/\1/p" "$d/cpu_stall_probe.txt" | tail -1; }
    pch=$(pv chunks); pst=$(pv cpu_stalls); pmax=$(pv max_cpu_us)
    pch=${pch:--} pst=${pst:--} pmax=${pmax:--}
  fi
  el=$(sv elapsed_s); lw=$(sv late_wakeups)
  [[ "$el" != - && "$lw" != - ]] && lpm=$(awk -v l="$lw" -v e="$el" 'BEGIN { printf "%.1f", (e > 0 ? l / (e / 60) : 0) }')
  r50=- target=- frms=- fmax=-
  [[ -s "$d/summary.json" ]] && r50=$(jq -r '.latency_us.p50' "$d/summary.json")
  c50=$(sv compute_p50_us)
  [[ -n "$echo_p50" && "$c50" != - ]] && target=$(awk -v e="$echo_p50" -v c="$c50" 'BEGIN { printf "%.0f", 1.3 * (e + c) }')
  if [[ -s "$d/result.csv" && -s "$WORK/${run}_sync/result.csv" ]]; then
    read -r frms fmax < <(awk -F, 'FNR == 1 { next } NR == FNR { if ($11 == 1) { f[$1] = $13 " " $14 " " $15 } next }
      $11 == 1 && ($1 in f) { split(f[$1], a, " "); dx = $13 - a[1]; dy = $14 - a[2]; dz = $15 - a[3]; e = sqrt(dx*dx + dy*dy + dz*dz)
        n++; s += e * e; if (e > m) m = e }
      END { if (n) printf "%.3f %.3f\n", sqrt(s / n), m; else print "- -" }' "$WORK/${run}_sync/result.csv" "$d/result.csv")
  fi
  echo "$run,$(sv deadline_misses),$(sv misses_compute),$(sv misses_late_wakeup),$lw,$lpm,$ctc,$ctl,$ctm,$ctmax,$(sv wake_latency_p99_us),$c50,$(sv geometry_thread),$(sv pd_update_rate_hz),$(sv model_age_p50_ticks),$(sv model_age_p99_ticks),$(sv model_age_max_ticks),$(sv pose_triggered),$r50,$target,$frms,$fmax,$(sv misses_stalled),$(sv tick_cpu_p99_us),$(sv tick_cpu_max_us),$pch,$pst,$pmax,$(sv misses_charged)" >> "$floor"
done

# Plots.
runs_list=$(awk -F, 'NR > 1 { printf "%s ", $1 }' "$csv")
loop_runs=$(awk -F, 'NR > 1 && $8 != "-" { printf "%s ", $1 }' "$csv")
gnuplot -e "dir='$OUT'; runs='$runs_list'; loop_runs='$loop_runs'" "$ROOT/bench/loop/loop_plots.gp"

# Markdown.
col() { awk -F, -v c="$1" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == c) k = i; next } { print $1, $k }' "$csv"; }
commit="$(meta commit)"; [[ "$(meta dirty)" == 1 ]] && commit="$commit (with uncommitted changes)"
cpu="$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//') ($(nproc) CPUs)"
secs=$(meta seconds_per_run)
held=$(awk -F, 'NR > 1 && $2 != "-" && $3 != "-" && $14 == "0" && $8 > 0 { if ($3 + 0 >= best) { best = $3 + 0; name = $1 } }
  END { if (name != "") print name, best }' "$csv")
fewest=$(awk -F, 'NR > 1 && $2 != "-" && $15 != "-" { if (best == "" || $15 + 0 < best) { best = $15 + 0; name = $1; tri = $3 } }
  END { if (name != "") print name, tri, best }' "$csv")
largest=$(awk -F, 'NR > 1 && $3 != "-" && $15 != "-" { if ($3 + 0 >= best) { best = $3 + 0; name = $1; m = $15; c99 = $18 } }
  END { if (name != "") print name, best, m, c99 }' "$csv")
md="$OUT/loop_latency.md"
{
  echo "# Servo loop rate and latency"
  echo
  echo "Generated by \`$(meta command)\` ($secs s per run); every number below was measured in that run."
  echo
  echo "| | |"; echo "|---|---|"
  echo "| CPU | $cpu |"
  echo "| Started | $(meta start_utc) |"
  echo "| Finished | $(meta end_utc) |"
  echo "| Commit | \`$commit\` |"
  echo "| Server build | $(meta server_build) |"
  echo "| Load average (1 min) over the runs | $(awk -F, 'NR > 1 { for (i = 6; i <= 7; i++) if ($i != "") { if (lo == "" || $i < lo) lo = $i; if ($i > hi) hi = $i } } END { print lo " to " hi }' "$csv") |"
  echo
  echo "Each run: \`haptic_server\` (or the transport-only \`echo_server\`) and \`probe_replay\` as separate processes over LCM udpm on loopback, in one private network namespace (\`scripts/netns_run.sh\`, \`probes/scripts/run_session.sh\`). The replay plays the scene's 1 kHz trajectory (bench-only scenes: \`bench/scenes/*.params.yaml\` through \`probe_sim\`, a 15 s press-and-slide; default scenes: \`probes/trajectories/*.csv\`), repeated to last $secs s. The server logs every tick (\`--timing-log\`); tick statistics cover the replay (first to last tick that rendered a new pose). The machine is a shared 2-core VM: other engineers' builds ran at the same time (load average column); compare runs only at similar load."
  echo
  echo "## Servo loop (server side)"
  echo
  echo "Compute = wake-up to wrench handed to LCM: PD for every object in reach, tool dynamics, coupling, limits, publish (wall-clock: it includes any time the thread lost the CPU). Jitter = |period - 1000 us|. A miss = a tick that finished after the next tick's start; in brackets, the misses whose wall-clock compute exceeded the 1 ms period (the others started late: the servo thread, SCHED_FIFO and pinned, was not running when its deadline came); the next section splits them by the tick's CPU time. Contact = ticks with at least one contact region. CPU = the server process's utime + stime (all threads) over the replay, in % of one core."
  echo
  echo "| Run | Scene triangles | Tool triangles | Ticks | Rate Hz | Jitter p50 / p99 / p99.9 / max us | Misses (wall compute > 1 ms) | Misses / min | Compute p50 / p99 / p99.9 / max us | Contact | Server CPU % | Load 1-min before / after |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
  awk -F, 'NR > 1 && $2 != "-" {
    contact = $21 == "-" ? "-" : sprintf("%.0f%%", 100 * $21)
    printf "| %s | %s | %s | %s | %s | %s / %s / %s / %s | %s (%s) | %s | %s / %s / %s / %s | %s | %s | %s / %s |\n",
      $1, $3, $4, $8, $9, $10, $11, $12, $13, $14, $33, $15, $17, $18, $19, $20, contact, $30, $6, $7 }' "$csv"
  echo
  echo "## Misses by cause, the platform's floor, the geometry thread"
  echo
  echo "From the server's summary line and \`cyclictest -m -p 79 -a 1 -i 1000\` run beside each run for the same time on the servo's CPU (the platform's floor). Misses split by cause (\`haptics/loop/miss_cause.h\`): compute (the tick's own CPU time, read with \`CLOCK_THREAD_CPUTIME_ID\` after each send, overran the period, and no tick of as much counted work ran in half a period earlier in the run: ours, to be zero), charged (its CPU time overran, but ticks of at least as much counted work ran in half a period of CPU time earlier in the run: time the platform charged to the thread, see the stall floor; work is counted only on ticks that render the geometry thread's contact model, as model terms, so with PD in the tick every CPU overrun is compute), stalled (its CPU time fit the period but the thread was not running for long enough inside the tick to miss: preempted by another thread or an interrupt, or the vCPU descheduled by the hypervisor: the platform's) and late wake-up (the tick started too late to finish: the platform's). Tick CPU p99 / max: the thread's CPU time per tick, beside the wall-clock compute of the first table. CPU stall floor: \`cpu_stall_probe\` beside each run on the servo's CPU (SCHED_FIFO 78, a fixed ~20 us chunk of work every ms): chunks charged 1 ms or more of CPU time (of all chunks; max us). The platform charges such time to whatever thread is running (interrupts, softirqs, a vCPU descheduled while the thread was on it); the servo's tick CPU time reads the same clock, which is why an overrun is counted as compute only if the tick's work does not explain it. Late wake-ups: wake-ups 1 ms or more after the tick's scheduled start (the pose's arrival in its window, or the deadline), per minute, against cyclictest's wake-ups 1 ms or more late per minute. Geometry: 1 = PD on the geometry thread (\`contact.geometry_thread\`), PD updates per second taken by the tick, and the age in ticks of the contact model it rendered. RTT target = 1.3 x (echo p50 + the server's compute p50). Force difference: |f| difference per pose against the same trajectory with \`--geometry-thread off\` (PD in the tick; the \`_sync\` rows), RMS and max over the poses both answered."
  echo
  echo "| Run | Misses: compute / charged / stalled / late wake-up | Tick CPU p99 / max us | CPU stall floor: chunks >= 1 ms (max us) | Late wake-ups / min (server) | cyclictest late >= 1 ms / min (max us) | Wake latency p99 us | Geometry thread | PD updates / s | Model age p50 / p99 / max ticks | Pose-triggered | RTT p50 us (target) | Force diff vs sync RMS / max N |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  awk -F, 'NR > 1 { printf "| %s | %s / %s / %s / %s | %s / %s | %s of %s (%s) | %s | %s (%s) | %s | %s | %s | %s / %s / %s | %s | %s (%s) | %s / %s |\n",
      $1, $3, $29, $23, $4, $24, $25, $27, $26, $28, $6, $9, $10, $11, $13, $14, $15, $16, $17, $18, $19, $20, $21, $22 }' "$floor"
  echo
  echo "## Round trip over LCM (replay side)"
  echo
  echo "Round trip = replay send to wrench receipt on the replay's clock. Superseded = a pose that arrived in the same servo period as a newer one (the fixed-rate loop renders the newest; the older is answered by that newer wrench); lost = never followed by an answer. RTT / echo = this run's p50 over the echo run's p50 (same sweep). Replay CPU in % of one core."
  echo
  echo "| Run | Poses sent | Answered | Superseded | Lost | RTT p50 us | RTT p99 us | RTT max us | RTT p50 / echo | Replay CPU % | Server CPU % | Max force N | Exit |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  awk -F, 'NR > 1 { printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n",
      $1, $22, $23, $24, $25, $26, $27, $28, $29, $31, $30, $32, $5 }' "$csv"
  echo
  echo "Exit: run_session.sh's code (0 = every pose answered or superseded, at most half superseded, finite, within the device limit; 1 = the replay's check failed; 2 = the server failed)."
  echo
  echo "## Findings"
  echo
  if [[ -n "$held" ]]; then
    read -r hname htris <<< "$held"
    echo "- **Largest scene that held 1 kHz with zero deadline misses: \`$hname\` ($htris scene triangles).**"
  else
    read -r fname ftris fmpm <<< "${fewest:-- - -}"
    echo "- **No scene held 1 kHz with zero deadline misses on this loaded 2-core VM.** Fewest: \`$fname\` ($ftris scene triangles) at $fmpm misses per minute."
  fi
  if [[ -n "$largest" ]]; then
    read -r lname ltris lmpm lc99 <<< "$largest"
    echo "- The largest scene, \`$lname\` ($ltris triangles), ran with $lmpm misses per minute and a compute p99 of $lc99 us."
  fi
  awk -F, -v e="${echo_p50:-}" 'NR > 1 && $2 != "-" && $29 != "-" { n++; if (lo == "" || $29 < lo) lo = $29; if ($29 > hi) hi = $29 }
    END { if (n && e != "") printf "- Round trip: the server is slower than the transport floor: p50 %s to %s times the echo'"'"'s %s us. A pose waits for the tick that renders it: with pose-triggered ticks (the default) the tick starts on the pose'"'"'s arrival once the phase lock has put arrivals inside the tick'"'"'s window, otherwise it waits up to a period (the server'"'"'s pose_wait_p50_us in server.out); the echo answers on receipt. Superseded poses: two poses in one period, the older is never rendered (at most one tick per period).\n", lo, hi, e }' "$csv"
  awk -F, 'NR > 1 && $2 != "-" && $26 != "-" { n++; if (lo == "" || $26 + 0 < lo) lo = $26 + 0; if ($26 + 0 > hi) hi = $26 + 0; s += $24; p += $22 }
    END { if (n) printf "- The round-trip p50 of the server runs spans %s to %s us and does not follow scene size: the replay and the server each keep their own 1 kHz clock, so where a pose lands in the server'"'"'s period (its wait for the next tick) is set by a phase that is random per run and drifts slowly. The same phase, with jitter on both sides, puts two poses into one period now and then: %.1f%% of the poses were superseded over all server runs.\n", lo, hi, 100 * s / p }' "$csv"
  awk -F, 'NR > 1 && $2 != "-" { m += $2; mc += $3; mh += $29; ms += $23; ml += $4; if ($3 + 0 > 0) bad = bad " `" $1 "`" }
    END { if (m) printf "- Of the %d deadline misses over all runs (server summary), %d were compute-caused (the tick'"'"'s own CPU time overran the period beyond what its work needs%s), %d charged (the CPU time overran but the same work ran in half a period elsewhere: the platform'"'"'s), %d stalled (the tick'"'"'s CPU time fit but the thread was not running: preempted or its vCPU descheduled) and %d late wake-ups (the SCHED_FIFO servo thread did not get the CPU at its start; cyclictest beside it measures the same floor).\n", m, mc, (mc ? ":" bad : ""), mh, ms, ml }' "$floor"
  awk -F, 'NR > 1 && $2 != "-" && $13 == "1" && $27 != "-" { n++; mc += $3; mh += $29; if ($3 + 0 > 0) runs++; pc += $26; ps += $27 }
    END { if (n) printf "- With the geometry thread (%d runs): %d compute-caused misses in %d runs, %d charged; the CPU stall probe beside them saw %d of %d fixed ~20 us chunks charged 1 ms or more of CPU time (the platform'"'"'s floor for the same clock).\n", n, mc, runs, mh, ps, pc }' "$floor"
  awk -F, 'NR > 1 && $3 != "-" && $3 + 0 > 0 && $18 != "-" { n++; if (lo == "" || $18 + 0 < lo) { lo = $18 + 0; ln = $1 } if ($18 + 0 > hi) { hi = $18 + 0; hn = $1 } }
    END { if (n) printf "- Compute p99 over the scenes with meshes ranges from %s us (`%s`) to %s us (`%s`); see the plot against scene size.\n", lo, ln, hi, hn }' "$csv"
  awk -F, 'NR > 1 && $2 != "-" && $21 != "-" { n++; if (lo == "" || $21 < lo) lo = $21; if ($21 > hi) hi = $21 }
    END { if (n) printf "- The tool was in contact on %.0f%% to %.0f%% of the ticks (per run in the table).\n", 100 * lo, 100 * hi }' "$csv"
  echo
  echo "## Plots"
  echo
  echo "![Round-trip CDF](loop_rtt_cdf.png)"
  echo
  echo "![Period jitter CDF](loop_jitter_cdf.png)"
  echo
  echo "![Compute against scene size](loop_compute_vs_size.png)"
  echo
  echo "Data: \`loop_latency.csv\` (one row per run), \`loop_distributions.csv\` (the plotted quantiles). Raw per-tick and per-pose files were in \`$WORK\` (not committed). Re-run: \`bench/run_loop_bench.sh\` (1 min per scene) or \`--quick\`."
} > "$md"
echo "loop_report: wrote $md, $csv, $dist and the PNGs in $OUT" >&2
