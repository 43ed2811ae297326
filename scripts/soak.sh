#!/usr/bin/env bash
# Soak run: haptic_server plus probe_replay looping a committed trajectory for
# a long time, in a private network namespace (re-runs itself through
# scripts/netns_run.sh when needed). Samples the server's resident memory
# (VmRSS in /proc/PID/status) every few seconds, logs every servo tick
# (haptic_server --timing-log), and judges the run:
#
#   scripts/soak.sh [--minutes M] [--seconds S] [--scene NAME] [--bin-dir DIR]
#                   [--out PREFIX] [--sample-s S] [--floor-s S]
#                   [--max-rss-growth-kb K] [--max-compute-misses N]
#
#   --minutes M   run length (default 30), rounded up to whole trajectories;
#                 --seconds S overrides it
#   --scene NAME  config/NAME.yaml with probes/trajectories/NAME.csv (default box_on_box)
#   --bin-dir D   where haptic_server and probe_replay are (default build/bin)
#   --out PREFIX  writes PREFIX.md and PREFIX.csv (default bench/results/soak)
#   --sample-s S  memory sampling period (default 5; at least 10 samples are taken)
#   --floor-s S   before the server starts, measure the machine's own late
#                 wake-ups with cyclictest for S s (default 60; 0 or no
#                 cyclictest: not measured); reported beside ours, not judged
#   --max-rss-growth-kb K    RSS growth allowed after warm-up (default 1024)
#   --max-compute-misses N   compute-caused misses allowed (default 0)
#
# Verdict PASS (exit 0) needs all of: the server kept running and stopped
# cleanly; every pose sent; RSS growth after warm-up <= 1 MiB; zero
# compute-caused misses (the server's misses_compute: ticks that finished
# after the next tick's start because their own CPU time overran the period
# beyond what their work needs, haptics/loop/miss_cause.h); zero poses lost;
# zero non-finite wrenches. Otherwise FAIL (exit 1) naming each failed
# measure. The platform's misses (late wake-ups: the VM did not run the
# SCHED_FIFO thread in time; stalled; charged) and superseded poses are
# reported, not judged: the machine's load decides them.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
minutes=30 seconds="" scene=box_on_box bin="$ROOT/build/bin" out="$ROOT/bench/results/soak" sample=5
floor_s=60 max_growth_kb=1024 max_compute_misses=0
args=("$@")
while (($#)); do
  case "$1" in
    --minutes) minutes="$2"; shift 2 ;;
    --seconds) seconds="$2"; shift 2 ;;
    --scene) scene="$2"; shift 2 ;;
    --bin-dir) bin="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --sample-s) sample="$2"; shift 2 ;;
    --floor-s) floor_s="$2"; shift 2 ;;
    --max-rss-growth-kb) max_growth_kb="$2"; shift 2 ;;
    --max-compute-misses) max_compute_misses="$2"; shift 2 ;;
    -h|--help) sed -n '2,34p' "$0"; exit 0 ;;
    *) echo "soak: unknown option '$1'" >&2; exit 2 ;;
  esac
done
num='^[0-9]+([.][0-9]+)?$'
[[ "$minutes" =~ $num ]] || { echo "soak: --minutes must be a positive number, got '$minutes'" >&2; exit 2; }
[[ -z "$seconds" || "$seconds" =~ $num ]] || { echo "soak: --seconds must be a positive number, got '$seconds'" >&2; exit 2; }
[[ "$sample" =~ $num ]] || { echo "soak: --sample-s must be a positive number, got '$sample'" >&2; exit 2; }
[[ "$floor_s" =~ ^[0-9]+$ ]] || { echo "soak: --floor-s must be a whole number of seconds, got '$floor_s'" >&2; exit 2; }
[[ "$max_growth_kb" =~ ^[0-9]+$ ]] || { echo "soak: --max-rss-growth-kb must be a whole number, got '$max_growth_kb'" >&2; exit 2; }
[[ "$max_compute_misses" =~ ^[0-9]+$ ]] || { echo "soak: --max-compute-misses must be a whole number, got '$max_compute_misses'" >&2; exit 2; }
duration=$(awk -v m="$minutes" -v s="$seconds" 'BEGIN { print (s != "" ? s : m * 60) }')
awk -v d="$duration" 'BEGIN { exit !(d >= 5) }' || { echo "soak: the run must last at least 5 s" >&2; exit 2; }
config="$ROOT/config/$scene.yaml" trajectory="$ROOT/probes/trajectories/$scene.csv"
[[ -f "$config" && -f "$trajectory" ]] || { echo "soak: no config/$scene.yaml with probes/trajectories/$scene.csv" >&2; exit 2; }
for b in haptic_server probe_replay; do
  [[ -x "$bin/$b" ]] || { echo "soak: $bin/$b not found (build first, or --bin-dir)" >&2; exit 2; }
done

# Only loopback visible, or re-run inside a private network namespace.
others=$(awk -F: 'NR > 2 { gsub(/ /, "", $1); if ($1 != "lo") print $1 }' /proc/net/dev)
if [[ -n "$others" ]]; then
  exec "$ROOT/scripts/netns_run.sh" "$0" "${args[@]}"
fi

work=$(mktemp -d "${TMPDIR:-/tmp}/soak.XXXXXX")
mkdir -p "$(dirname "$out")"
# Trajectory length (s): the last sample's time plus one period.
traj_s=$(awk -F, 'NR > 1 && $1 !~ /^#/ && NF > 1 { n++; prev = last; last = $1 }
                  END { print last + (n > 1 ? last - prev : 0.001) }' "$trajectory")
repeat=$(awk -v d="$duration" -v t="$traj_s" 'BEGIN { r = int(d / t); if (r * t < d) r++; print (r < 1 ? 1 : r) }')
duration=$(awk -v r="$repeat" -v t="$traj_s" 'BEGIN { print r * t }')
sample=$(awk -v d="$duration" -v s="$sample" 'BEGIN { print (d / 10 < s ? d / 10 : s) }')
echo "soak: $scene for ${duration} s (${repeat} x ${traj_s} s trajectory), memory every ${sample} s; work dir $work"

# The machine's own floor, just before the run: cyclictest as the shared
# notes give it (SCHED_FIFO 80, CPU 1, 1 kHz), wake-ups >= 1 ms late.
floor_text="not measured (--floor-s 0)"
if ((floor_s > 0)); then
  if command -v cyclictest >/dev/null 2>&1; then
    cpu=$(( $(nproc) > 1 ? 1 : 0 ))
    echo "soak: measuring the machine's late wake-up floor with cyclictest for ${floor_s} s"
    if cyclictest -m -p 80 -a "$cpu" -t 1 -i 1000 -D "$floor_s" -q -h 2000 >"$work/cyclictest.txt" 2>&1; then
      # Histogram rows are "<us> <count>" up to 1999 us; later ones are overflows.
      floor_text=$(awk -v d="$floor_s" '!/^#/ && NF >= 2 { n += $2; if ($1 + 0 >= 1000) late += $2 }
        /^# Histogram Overflows:/ { over = $4 + 0 }
        END { late += over; n += over
              printf "%d of %d cycles >= 1 ms late in %d s (%.1f per min; %d >= 2 ms)", late, n, d, late / (d / 60), over }' \
        "$work/cyclictest.txt")
    else
      floor_text="cyclictest failed: $(tail -n 1 "$work/cyclictest.txt")"
    fi
  else
    floor_text="not measured (no cyclictest: apt-get install rt-tests)"
  fi
fi

rate_hz=$(awk '$1 == "rate_hz:" { print $2; exit }' "$config")
rate_hz=${rate_hz:-1000}
# Room for every tick of the run plus start-up and shutdown; the records are
# allocated (and touched) before the loop starts, so RSS does not grow with them.
log_ticks=$(awk -v d="$duration" -v r="$rate_hz" 'BEGIN { printf "%d", (d + 120) * r }')
"$bin/haptic_server" --config "$config" --timing-log "$work/ticks.csv" --timing-log-ticks "$log_ticks" \
  >"$work/server.out" 2>"$work/server.err" &
server=$!
cleanup() { kill -INT "$server" 2>/dev/null || true; }
trap cleanup EXIT
"$bin/probe_replay" --trajectory "$trajectory" --repeat "$repeat" --summary "$work/summary.json" \
  --max-superseded 1 --start-delay 30 --realtime >"$work/replay.out" 2>"$work/replay.err" &
replay=$!

rss_kb() { awk '/^VmRSS:/ { print $2 }' "/proc/$1/status" 2>/dev/null || true; }
echo "t_s,server_rss_kb" >"$out.csv"
start_ns=$(date +%s%N)
while kill -0 "$replay" 2>/dev/null; do
  kill -0 "$server" 2>/dev/null || break
  r=$(rss_kb "$server")
  t=$(awk -v a="$start_ns" -v b="$(date +%s%N)" 'BEGIN { printf "%.1f", (b - a) / 1e9 }')
  [[ -n "$r" ]] && echo "$t,$r" >>"$out.csv"
  sleep "$sample"
done
server_alive=0
kill -0 "$server" 2>/dev/null && server_alive=1
set +e
wait "$replay"; replay_rc=$?
kill -INT "$server" 2>/dev/null; wait "$server"; server_rc=$?
set -e
trap - EXIT
summary=$(grep '^haptic_server summary:' "$work/server.out" | tail -n 1 || true)

field() { grep -o "$1=[0-9.]*" <<<"$summary" | head -n 1 | cut -d= -f2; }
json() { grep -o "\"$1\": [0-9.a-z]*" "$work/summary.json" 2>/dev/null | head -n 1 | awk '{ print $2 }'; }
samples=$(($(wc -l <"$out.csv") - 1))
read -r rss_start rss_warm rss_end rss_max < <(awk -F, -v d="$duration" '
  NR > 1 { n++; t[n] = $1; r[n] = $2; if ($2 > max) max = $2 }
  END { if (n == 0) { print "0 0 0 0"; exit }
        w = 1; for (i = 1; i <= n; i++) if (t[i] <= (d * 0.25 < 60 ? d * 0.25 : 60)) w = i
        print r[1], r[w], r[n], max }' "$out.csv")
growth_kb=$((rss_end - rss_warm))
sent=$(json poses_sent) lost=$(json lost) superseded=$(json superseded) nonfinite=$(json non_finite_answers)
ticks=$(field ticks) misses=$(field deadline_misses)
# The misses by cause, as the server classified them (haptics/loop/miss_cause.h):
# compute is ours; charged, stalled and late wake-ups are the platform's.
compute_misses=$(field misses_compute) charged_misses=$(field misses_charged)
stalled_misses=$(field misses_stalled) late_wake_misses=$(field misses_late_wakeup)
# The per-tick log: every tick logged, and how many took longer than the period.
read -r log_rows not_logged over_period < <(awk -F, '
  /^#/ { m = split($0, words, " ")
         for (i = 1; i <= m; i++) { split(words[i], kv, "="); if (kv[1] == "nominal_period_us") p = kv[2]
                                    if (kv[1] == "ticks_not_logged") nl = kv[2] }
         next }
  $1 == "tick" { next }
  { n++; o += ($3 + 0 > p + 0) }
  END { if (p == "" || nl == "") { print "0 - -"; exit } printf "%d %d %d\n", n, nl, o }' \
  "$work/ticks.csv" 2>/dev/null || echo "0 - -")
growth_ok=$(awk -v g="$growth_kb" -v m="$max_growth_kb" 'BEGIN { print (g <= m) ? 1 : 0 }')
verdict=PASS problems=()
((server_alive)) || problems+=("the server died during the run")
((server_rc == 0)) || problems+=("the server exited $server_rc")
[[ -n "$summary" ]] || problems+=("no server summary line")
[[ -n "$sent" ]] || problems+=("no replay summary (replay exit $replay_rc; $(tail -n 1 "$work/replay.err" 2>/dev/null))")
[[ -z "$sent" || "$sent" -eq $((repeat * $(($(grep -c '^[0-9]' "$trajectory"))))) ]] || problems+=("not every pose was sent")
[[ -n "$lost" ]] || problems+=("no lost-pose count")
[[ -z "$lost" || "$lost" -eq 0 ]] || problems+=("$lost poses lost")
[[ -n "$nonfinite" ]] || problems+=("no non-finite wrench count")
[[ -z "$nonfinite" || "$nonfinite" -eq 0 ]] || problems+=("$nonfinite non-finite wrenches")
((samples >= 2)) || problems+=("fewer than 2 memory samples")
((growth_ok)) || problems+=("RSS grew ${growth_kb} kB after warm-up (limit ${max_growth_kb} kB)")
if [[ "$not_logged" == - ]]; then
  problems+=("no tick timing log ($work/ticks.csv)")
else
  ((not_logged == 0)) || problems+=("$not_logged ticks not in the timing log")
fi
if [[ -z "$compute_misses" ]]; then
  problems+=("no misses_compute in the server summary")
  compute_misses=-
else
  ((compute_misses <= max_compute_misses)) ||
    problems+=("$compute_misses compute-caused misses (limit $max_compute_misses)")
fi
((${#problems[@]} == 0)) || verdict=FAIL

{
  echo "# Soak run: $scene, $(awk -v d="$duration" 'BEGIN { printf "%.1f", d / 60 }') min"
  echo
  echo "Generated by \`scripts/soak.sh\` on $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)."
  echo "haptic_server (config/$scene.yaml) and probe_replay (probes/trajectories/$scene.csv, ${repeat} times"
  echo "back to back) over LCM udpm in a private network namespace. Memory: the server's VmRSS every ${sample} s"
  echo "(${samples} samples in \`$(basename "$out").csv\`); warm-up ends at min(25 % of the run, 60 s)."
  echo
  echo "| measure | value |"
  echo "|---|---|"
  echo "| verdict | $verdict$( ((${#problems[@]})) && printf ': %s' "$(IFS=';'; echo "${problems[*]}" | sed 's/;/; /g')") |"
  echo "| server RSS start / after warm-up / end / max | $rss_start / $rss_warm / $rss_end / $rss_max kB |"
  echo "| RSS growth after warm-up (judged: <= $max_growth_kb kB) | $growth_kb kB ($(awk -v g="$growth_kb" -v d="$duration" 'BEGIN { printf "%.2f", g / (d / 3600) }') kB/h) |"
  echo "| ticks / deadline misses | $ticks / $misses ($(awk -v m="${misses:-0}" -v d="$duration" 'BEGIN { printf "%.1f", m / (d / 60) }') per min) |"
  echo "| compute-caused misses (judged: <= $max_compute_misses) | $compute_misses |"
  echo "| late wake-up misses (not judged) | ${late_wake_misses:--} ($(awk -v m="$late_wake_misses" -v d="$duration" 'BEGIN { printf "%.1f", (m + 0) / (d / 60) }') per min) |"
  echo "| charged / stalled misses (the platform's, not judged) | ${charged_misses:--} / ${stalled_misses:--} |"
  echo "| machine floor: cyclictest before the run (not judged) | $floor_text |"
  echo "| ticks with compute > period (missed or not) | $over_period of $log_rows logged |"
  echo "| poses sent / lost (judged: 0) / superseded | ${sent:-?} / ${lost:-?} / ${superseded:-?} |"
  echo "| non-finite wrenches (judged: 0) | ${nonfinite:-?} |"
  echo
  echo "A miss is a tick that finished after the next tick's start, split by cause as the server counts"
  echo "them (haptics/loop/miss_cause.h). Compute-caused: the tick's own CPU time overran the ${rate_hz} Hz"
  echo "period and no tick of as much counted work ran in half a period (ours). Charged: its CPU time"
  echo "overran, but the same work ran in half a period elsewhere (time the platform charged to the"
  echo "thread). Stalled: its CPU time fit but the thread was not running. Late wake-up: the thread woke"
  echo "too late to finish (the VM did not run it in time)."
  echo
  echo "Server exit summary:"
  echo
  echo "    $summary"
} >"$out.md"
cat "$out.md"
echo "soak: wrote $out.md and $out.csv"
if [[ "$verdict" != PASS ]]; then
  for p in "${problems[@]}"; do echo "soak: FAIL: $p" >&2; done
  exit 1
fi
echo "soak: PASS"
rm -rf "$work"
