#!/usr/bin/env bash
# Servo-loop benchmark: the real haptic_server and probe_replay as separate
# processes over LCM UDP multicast, inside a private network namespace
# (scripts/netns_run.sh), for every scene in the table below (a box pair up
# to 164k scene triangles, mesh tools of 5.8k-6.4k triangles against 20k-164k
# scene triangles, the default scenes), plus the transport-only echo_server
# as the floor. Beside every run, for the same time, cyclictest measures the
# platform's own late wake-ups (the floor the server's are compared with).
# Every scene with a mesh tool runs a second time with --geometry-thread off
# (PD in the tick) on the same trajectory, for the force difference the
# geometry thread makes. Writes bench/results/loop_latency.md, .csv and PNG
# plots (bench/loop/loop_report.sh).
#
#   bench/run_loop_bench.sh [--minutes M] [--quick] [--only a,b,...]
#
#   --minutes M  length of each run (default 1)
#   --quick      6 s per run (the whole sweep in under 3 minutes)
#   --only LIST  run only these scenes (and the echo), comma-separated
# Environment: BUILD_DIR (default build/) is where it configures and builds
# the four executables it needs; LOOP_BENCH_OUT (default bench/results) is
# where the report goes; LOOP_BENCH_REUSE=DIR re-writes the report from an
# earlier run's work directory without running anything.
#
# Each run replays the scene's trajectory (a committed CSV, or a probe_sim
# parameter file turned into one), repeated to the run length, with
# haptic_server --timing-log recording every tick; the server's CPU use is
# read from /proc over the replay (bench/loop/loop_cpu.sh).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"

# The scenes, in run order: name, config file, trajectory (.csv as is, or a
# probe_sim .params.yaml), all relative to the repository. A scene whose
# config file does not exist (yet) is skipped with a message.
SCENES=(
  "box_pair             bench/scenes/box_pair.yaml             bench/scenes/box_pair.params.yaml"
  "ball_on_sphere_1k    bench/scenes/ball_on_sphere_1k.yaml    bench/scenes/ball_on_sphere_1k.params.yaml"
  "ball_on_sphere_5k    bench/scenes/ball_on_sphere_5k.yaml    bench/scenes/ball_on_sphere_5k.params.yaml"
  "knot_6k              bench/scenes/knot_6k.yaml              bench/scenes/knot_6k.params.yaml"
  "camel_20k            bench/scenes/camel_20k.yaml            bench/scenes/camel_20k.params.yaml"
  "ball_on_sphere_20k   bench/scenes/ball_on_sphere_20k.yaml   bench/scenes/ball_on_sphere_20k.params.yaml"
  "armadillo_52k        bench/scenes/armadillo_52k.yaml        bench/scenes/armadillo_52k.params.yaml"
  "bunny_75k            bench/scenes/bunny_75k.yaml            bench/scenes/bunny_75k.params.yaml"
  "elephant_bunny_164k  bench/scenes/elephant_bunny_164k.yaml  bench/scenes/elephant_bunny_164k.params.yaml"
  "cow_tool_camel_20k   bench/scenes/cow_tool_camel_20k.yaml   bench/scenes/cow_tool_camel_20k.params.yaml"
  "knot_on_bunny        config/knot_on_bunny.yaml              probes/trajectories/knot_on_bunny.csv"
  "knot_tool_elephant_bunny_164k bench/scenes/knot_tool_elephant_bunny_164k.yaml bench/scenes/knot_tool_elephant_bunny_164k.params.yaml"
  "box_on_box           config/box_on_box.yaml                 probes/trajectories/box_on_box.csv"
  "box_on_box_no_phase_lock bench/scenes/box_on_box_no_phase_lock.yaml probes/trajectories/box_on_box.csv"
  "box_on_box_fixed_rate bench/scenes/box_on_box_fixed_rate.yaml probes/trajectories/box_on_box.csv"
  "spoon_in_cup         config/spoon_in_cup.yaml               probes/trajectories/spoon_in_cup.csv"
  "peg_in_hole          config/peg_in_hole.yaml                probes/trajectories/peg_in_hole.csv"
  "primitives_only      config/primitives_only.yaml            probes/trajectories/primitives_only.csv"
  "table_objects        config/table_objects.yaml              probes/trajectories/table_objects.csv"
  "many_objects         config/many_objects.yaml               probes/trajectories/many_objects.csv"
)

MINUTES=1 QUICK=0 ONLY=""
while (($#)); do
  case "$1" in
    --minutes) MINUTES="${2:-}"; shift 2 ;;
    --quick) QUICK=1; shift ;;
    --only) ONLY="${2:-}"; shift 2 ;;
    -h|--help) sed -n '2,22p' "$0"; exit 0 ;;
    *) echo "run_loop_bench: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$MINUTES" =~ ^[0-9]+([.][0-9]+)?$ ]] && awk -v m="$MINUTES" 'BEGIN { exit !(m > 0) }' ||
  { echo "run_loop_bench: --minutes '$MINUTES' is not a positive number" >&2; exit 2; }
SECONDS_PER_RUN=$(awk -v m="$MINUTES" -v q="$QUICK" 'BEGIN { print q ? 6 : int(m * 60 + 0.5) }')
selected() { [[ -z "$ONLY" || ",$ONLY," == *",$1,"* ]]; }
if [[ -n "$ONLY" ]]; then
  known=" $(for row in "${SCENES[@]}"; do read -r n _ <<< "$row"; printf '%s ' "$n"; done)"
  for want in ${ONLY//,/ }; do
    [[ "$known" == *" $want "* ]] || { echo "run_loop_bench: --only: no scene '$want' (scenes:$known)" >&2; exit 2; }
  done
fi

BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
BIN="$BUILD_DIR/bin"
OUT="${LOOP_BENCH_OUT:-$ROOT/bench/results}"
WORK="${LOOP_BENCH_REUSE:-}"
if [[ -n "$WORK" ]]; then
  exec "$ROOT/bench/loop/loop_report.sh" "$WORK" "$OUT"
fi

"$ROOT/scripts/install_deps.sh" >/dev/null
echo "run_loop_bench: building haptic_server, probe_replay, probe_sim, echo_server, cpu_stall_probe in $BUILD_DIR" >&2
cmake -S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD_DIR" -j"$(nproc)" --target haptic_server probe_replay probe_sim echo_server cpu_stall_probe >/dev/null
# The bench scenes name their meshes as ../../build/meshes/*.off.
"$ROOT/scripts/fetch_meshes.sh" "$ROOT/build/meshes" >/dev/null

WORK="$(mktemp -d /tmp/loop_bench.XXXXXX)"
echo "run_loop_bench: $SECONDS_PER_RUN s per run; work directory $WORK" >&2
{
  echo "seconds_per_run=$SECONDS_PER_RUN"
  echo "command=bench/run_loop_bench.sh $([[ $QUICK == 1 ]] && echo --quick || echo "--minutes $MINUTES")"
  echo "commit=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  # The committed reports (bench/results) are outputs, not the code measured.
  echo "dirty=$([[ -n "$(git -C "$ROOT" status --porcelain -- . ':!bench/results' 2>/dev/null)" ]] && echo 1 || echo 0)"
  echo "start_utc=$(date -u '+%Y-%m-%d %H:%M:%S UTC')"
  echo "server_build=$("$BIN/haptic_server" --version)"  # version, build type, CPU level
} > "$WORK/meta.txt"

# Repeats a CSV trajectory (time,x,y,z,qw,qx,qy,qz) until it lasts `seconds`.
repeat_trajectory() {
  local src="$1" seconds="$2" dst="$3"
  awk -F, -v want="$seconds" 'BEGIN { n = 0 } NR == 1 { print; next }
    /^[[:space:]]*(#|$)/ { next }
    { t[n] = $1; rest[n] = substr($0, length($1) + 1); n++ }
    END {
      period = t[n - 1] - t[0] + 0.001; shift = 0
      while (shift < want) {
        for (i = 0; i < n && shift + t[i] - t[0] < want; i++)
          printf "%.6f%s\n", shift + t[i] - t[0], rest[i]
        shift += period
      }
    }' "$src" > "$dst"
}

# run_one NAME CONFIG TRAJECTORY_SOURCE SERVER_EXE [SERVER_ARGS...]
run_one() {
  local name="$1" config="$2" traj_src="$3" server_exe="$4"; shift 4
  local dir="$WORK/$name"
  mkdir -p "$dir"
  if [[ "$traj_src" == *.params.yaml ]]; then
    "$BIN/probe_sim" --params "$traj_src" --csv-out "$dir/one_cycle.csv" >/dev/null
    traj_src="$dir/one_cycle.csv"
  fi
  repeat_trajectory "$traj_src" "$SECONDS_PER_RUN" "$dir/trajectory.csv"
  # The replay, wrapped so that both processes' CPU time is read (loop_cpu.sh).
  printf '#!/bin/sh\nexec "%s" "%s" "%s" -- "%s" "$@"\n' "$ROOT/bench/loop/loop_cpu.sh" "$server_exe" \
    "$dir/cpu.txt" "$BIN/probe_replay" > "$dir/replay_wrapped"
  chmod +x "$dir/replay_wrapped"
  {
    echo "name=$name"
    echo "config=$config"
    echo "load_before=$(cut -d' ' -f1-3 /proc/loadavg)"
  } > "$dir/run.txt"
  local t0=$SECONDS rc=0
  # The platform's floor over the same time: cyclictest at 1 kHz, SCHED_FIFO
  # just below the server's servo thread, pinned to the servo's CPU.
  local ct_pid=""
  if command -v cyclictest >/dev/null; then
    cyclictest -m -p 79 -a 1 -t 1 -i 1000 -D "$((SECONDS_PER_RUN + 4))" -q -h 20000 > "$dir/cyclictest.txt" 2>&1 &
    ct_pid=$!
  fi
  # The floor for CPU time the platform charges a running thread (a
  # fixed 20 us chunk per ms, SCHED_FIFO below cyclictest, same CPU): what
  # the server's compute-caused count cannot tell from its own compute.
  local probe_pid=""
  "$BIN/cpu_stall_probe" --cpu 1 --priority 78 --seconds "$((SECONDS_PER_RUN + 4))" > "$dir/cpu_stall_probe.txt" 2>&1 &
  probe_pid=$!
  "$ROOT/scripts/netns_run.sh" "$ROOT/probes/scripts/run_session.sh" \
    --out-dir "$dir" --replay "$dir/replay_wrapped" --trajectory "$dir/trajectory.csv" \
    --replay-arg --max-superseded --replay-arg 0.5 -- "$server_exe" "$@" > "$dir/session.log" 2>&1 || rc=$?
  [[ -n "$ct_pid" ]] && { wait "$ct_pid" || echo "run_loop_bench: $name: cyclictest failed (see $dir/cyclictest.txt)" >&2; }
  wait "$probe_pid" || echo "run_loop_bench: $name: cpu_stall_probe failed (see $dir/cpu_stall_probe.txt)" >&2
  { echo "exit=$rc"; echo "load_after=$(cut -d' ' -f1-3 /proc/loadavg)"; } >> "$dir/run.txt"
  local line
  line=$(grep -h "haptic_server summary" "$dir/server.out" 2>/dev/null | tail -1 |
         sed -n 's/.*rate_hz=\([^ ]*\) deadline_misses=\([^ ]*\).*/rate \1 Hz, misses \2/p' || true)
  echo "run_loop_bench: $name done in $((SECONDS - t0)) s (exit $rc${line:+; $line}; load $(cut -d' ' -f1 /proc/loadavg))" >&2
  echo "$name" >> "$WORK/runs.txt"
}


runs=()
for row in "${SCENES[@]}"; do
  read -r name config traj <<< "$row"
  selected "$name" || continue
  if [[ ! -f "$ROOT/$config" ]]; then
    echo "run_loop_bench: $name skipped: $config does not exist" >&2; continue
  fi
  if [[ ! -f "$ROOT/$traj" ]]; then
    echo "run_loop_bench: $name skipped: no trajectory $traj" >&2; continue
  fi
  runs+=("$row")
done
echo "run_loop_bench: ${#runs[@]} scenes + echo, about $(( (${#runs[@]} + 1) * (SECONDS_PER_RUN + 3) )) s" >&2

# The transport floor first, then the scenes.
i=0
echo "run_loop_bench: [$((++i))/$(( ${#runs[@]} + 1 ))] echo (transport only)" >&2
run_one echo "-" "$ROOT/bench/scenes/box_pair.params.yaml" "$BIN/echo_server"
for row in "${runs[@]}"; do
  read -r name config traj <<< "$row"
  echo "run_loop_bench: [$((++i))/$(( ${#runs[@]} + 1 ))] $name ($config)" >&2
  run_one "$name" "$config" "$ROOT/$traj" "$BIN/haptic_server" --config "$ROOT/$config" \
    --timing-log "$WORK/$name/ticks.csv" --timing-log-ticks $(( (SECONDS_PER_RUN + 120) * 1000 ))
  # Mesh tools: the same trajectory with PD in the tick, for the force difference.
  if grep -q "file: .*knot1.off\|file: .*cow.off" <(sed -n '/^tool:/,/^objects:/p' "$ROOT/$config"); then
    echo "run_loop_bench: [$i] ${name}_sync (--geometry-thread off)" >&2
    run_one "${name}_sync" "$config" "$ROOT/$traj" "$BIN/haptic_server" --config "$ROOT/$config" \
      --geometry-thread off \
      --timing-log "$WORK/${name}_sync/ticks.csv" --timing-log-ticks $(( (SECONDS_PER_RUN + 120) * 1000 ))
  fi
done
echo "end_utc=$(date -u '+%Y-%m-%d %H:%M:%S UTC')" >> "$WORK/meta.txt"

"$ROOT/bench/loop/loop_report.sh" "$WORK" "$OUT"
