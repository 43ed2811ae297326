#!/usr/bin/env bash
# Soak run: haptic_server plus probe_replay looping a committed trajectory for
# a long time, in a private network namespace (re-runs itself through
# scripts/netns_run.sh when needed). Samples the server's resident memory
# (VmRSS in /proc/PID/status) every few seconds and reports memory at start,
# after warm-up and at the end (growth), deadline misses, poses lost or
# superseded, and the server's counters:
#
#   scripts/soak.sh [--minutes M] [--seconds S] [--scene NAME] [--bin-dir DIR]
#                   [--out PREFIX] [--sample-s S]
#
#   --minutes M   run length (default 30), rounded up to whole trajectories;
#                 --seconds S overrides it
#   --scene NAME  config/NAME.yaml with probes/trajectories/NAME.csv (default box_on_box)
#   --bin-dir D   where haptic_server and probe_replay are (default build/bin)
#   --out PREFIX  writes PREFIX.md and PREFIX.csv (default bench/results/soak)
#   --sample-s S  memory sampling period (default 5; at least 10 samples are taken)
#
# Exit 0 when the run completed: the server kept running and stopped cleanly,
# every pose was sent, none was lost and every wrench was finite. Memory
# growth, deadline misses and superseded poses are reported, not judged (the
# machine's load decides them); the report says what they were.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
minutes=30 seconds="" scene=box_on_box bin="$ROOT/build/bin" out="$ROOT/bench/results/soak" sample=5
args=("$@")
while (($#)); do
  case "$1" in
    --minutes) minutes="$2"; shift 2 ;;
    --seconds) seconds="$2"; shift 2 ;;
    --scene) scene="$2"; shift 2 ;;
    --bin-dir) bin="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --sample-s) sample="$2"; shift 2 ;;
    -h|--help) sed -n '2,21p' "$0"; exit 0 ;;
    *) echo "soak: unknown option '$1'" >&2; exit 2 ;;
  esac
done
num='^[0-9]+([.][0-9]+)?$'
[[ "$minutes" =~ $num ]] || { echo "soak: --minutes must be a positive number, got '$minutes'" >&2; exit 2; }
[[ -z "$seconds" || "$seconds" =~ $num ]] || { echo "soak: --seconds must be a positive number, got '$seconds'" >&2; exit 2; }
[[ "$sample" =~ $num ]] || { echo "soak: --sample-s must be a positive number, got '$sample'" >&2; exit 2; }
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

"$bin/haptic_server" --config "$config" >"$work/server.out" 2>"$work/server.err" &
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
verdict=PASS problems=()
((server_alive)) || problems+=("the server died during the run")
((server_rc == 0)) || problems+=("the server exited $server_rc")
[[ -n "$summary" ]] || problems+=("no server summary line")
[[ -n "$sent" ]] || problems+=("no replay summary (replay exit $replay_rc; $(tail -n 1 "$work/replay.err" 2>/dev/null))")
[[ -z "$sent" || "$sent" -eq $((repeat * $(($(grep -c '^[0-9]' "$trajectory"))))) ]] || problems+=("not every pose was sent")
[[ -z "$lost" || "$lost" -eq 0 ]] || problems+=("$lost poses lost")
[[ -z "$nonfinite" || "$nonfinite" -eq 0 ]] || problems+=("$nonfinite non-finite wrenches")
((samples >= 2)) || problems+=("fewer than 2 memory samples")
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
  echo "| verdict | $verdict${problems[*]:+: ${problems[*]}} |"
  echo "| server RSS start / after warm-up / end / max | $rss_start / $rss_warm / $rss_end / $rss_max kB |"
  echo "| RSS growth after warm-up | $growth_kb kB ($(awk -v g="$growth_kb" -v d="$duration" 'BEGIN { printf "%.2f", g / (d / 3600) }') kB/h) |"
  echo "| ticks / deadline misses | $ticks / $misses ($(awk -v m="${misses:-0}" -v d="$duration" 'BEGIN { printf "%.1f", m / (d / 60) }') per min) |"
  echo "| poses sent / lost / superseded | ${sent:-?} / ${lost:-?} / ${superseded:-?} |"
  echo "| non-finite wrenches | ${nonfinite:-?} |"
  echo
  echo "Server exit summary:"
  echo
  echo "    $summary"
} >"$out.md"
cat "$out.md"
echo "soak: wrote $out.md and $out.csv"
[[ "$verdict" == PASS ]] || exit 1
