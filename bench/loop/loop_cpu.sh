#!/usr/bin/env bash
# CPU use of the loop benchmark's processes, read from /proc/<pid>/stat
# (utime + stime, all threads). bench/run_loop_bench.sh runs the replay
# through it, in place of probe_replay, under probes/scripts/run_session.sh:
#
#   loop_cpu.sh SERVER_EXE OUTFILE -- REPLAY_CMD [ARGS...]
#
# Finds the server among its parent's children (the process whose
# executable is SERVER_EXE: run_session starts the server and the replay),
# reads its CPU time, runs REPLAY_CMD in the foreground, reads the server's
# CPU time again, and writes OUTFILE as one line:
#   wall_s=... server_cpu_s=... replay_cpu_s=... server_pid=...
# server_cpu_s is the server's CPU time over the replay; replay_cpu_s is the
# replay's own user + system time (bash `times`, before and after). Exits
# with the replay's exit code.
set -uo pipefail
(($# >= 4)) && [[ "$3" == "--" ]] || {
  echo "loop_cpu: usage: loop_cpu.sh SERVER_EXE OUTFILE -- REPLAY_CMD [ARGS...]" >&2; exit 2; }
server_exe="$(readlink -f "$1")" out="$2"; shift 3
hz=$(getconf CLK_TCK)

# Sets CPU_TICKS to utime + stime of pid $1 (empty if it is gone).
read_cpu_ticks() {
  local line rest
  local -a f
  CPU_TICKS=""
  read -r line < "/proc/$1/stat" 2>/dev/null || return 0
  rest="${line##*) }"  # drop "pid (comm) ": comm may hold spaces
  read -r -a f <<< "$rest"
  CPU_TICKS=$((f[11] + f[12]))  # fields 14 and 15 of stat(5)
}

spid=""
for _ in $(seq 50); do
  kids=(); read -r -a kids < "/proc/$PPID/task/$PPID/children" || true  # no newline at its end
  for k in "${kids[@]}"; do
    [[ "$k" != "$$" && "$(readlink -f "/proc/$k/exe" 2>/dev/null)" == "$server_exe" ]] && spid=$k
  done
  [[ -n "$spid" ]] && break
  sleep 0.1
done
[[ -n "$spid" ]] || echo "loop_cpu: no child of $PPID runs $server_exe; server CPU not measured" >&2

# `times` must run in this shell (a subshell has no children of its own);
# its second line is the reaped children's user and system time.
times > "$out.before"
[[ -n "$spid" ]] && read_cpu_ticks "$spid"; s0=${CPU_TICKS:-}; t0=$EPOCHREALTIME
"$@"; rc=$?
[[ -n "$spid" ]] && read_cpu_ticks "$spid"; s1=${CPU_TICKS:-}; t1=$EPOCHREALTIME
times > "$out.after"
awk -v t0="$t0" -v t1="$t1" -v s0="$s0" -v s1="$s1" -v hz="$hz" -v pid="$spid" '
  function secs(x,  ms) { split(x, ms, "m"); sub(/s$/, "", ms[2]); return ms[1] * 60 + ms[2] }
  FNR == 2 { cpu += (FILENAME ~ /after$/ ? 1 : -1) * (secs($1) + secs($2)) }
  END {
    server = (s0 == "" || s1 == "") ? "nan" : sprintf("%.3f", (s1 - s0) / hz)
    printf "wall_s=%.3f server_cpu_s=%s replay_cpu_s=%.3f server_pid=%s\n", t1 - t0, server, cpu, pid
  }' "$out.before" "$out.after" > "$out"
rm -f "$out.before" "$out.after"
exit "$rc"
