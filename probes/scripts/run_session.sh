#!/usr/bin/env bash
# One server + replay session. Must already run inside a private network
# namespace (scripts/netns_run.sh); refuses otherwise. Used by scripts/demo.sh
# and the e2e tests.
#
#   run_session.sh --out-dir DIR --replay BIN --trajectory FILE
#                  [--max-force N] [--alongside 'SHELL CMD'] [--replay-arg ARG]...
#                  -- SERVER_CMD [ARGS...]
#
# Starts SERVER_CMD, runs probe_replay against it (and the optional
# --alongside command in the background at the same time), then stops the
# server with SIGINT. Leaves in DIR: server.out/.err, replay.out/.err,
# result.csv, summary.json, alongside.out. Prints the replay summary and the
# server's last stdout line (its exit summary).
# Exit: 0 all good; 1 the replay reported a failure; 2 the server failed
# (could not start, exited early or non-zero, did not stop); 3 usage; 4 the
# --alongside command failed; 125 not in a private network namespace (1 under
# CI=true, where a missing prerequisite fails).
set -euo pipefail

die_usage() { echo "run_session: $1" >&2; exit 3; }
out_dir="" replay="" trajectory="" max_force="" alongside=""
replay_args=()
while (($#)); do
  case "$1" in
    --out-dir) out_dir="$2"; shift 2 ;;
    --replay) replay="$2"; shift 2 ;;
    --trajectory) trajectory="$2"; shift 2 ;;
    --max-force) max_force="$2"; shift 2 ;;
    --alongside) alongside="$2"; shift 2 ;;
    --replay-arg) replay_args+=("$2"); shift 2 ;;
    --) shift; break ;;
    *) die_usage "unknown option '$1'" ;;
  esac
done
(($#)) || die_usage "no server command after --"
[[ -n "$out_dir" && -n "$replay" && -n "$trajectory" ]] || die_usage "--out-dir, --replay and --trajectory are required"
[[ -x "$replay" ]] || die_usage "replay binary '$replay' not found or not executable (build first)"
[[ -x "$1" ]] || command -v "$1" >/dev/null || die_usage "server '$1' not found or not executable (build first)"
[[ -f "$trajectory" ]] || die_usage "trajectory '$trajectory' not found"

# Defence in depth: udpm multicast only where nothing but loopback exists.
others=$(awk -F: 'NR > 2 { gsub(/ /, "", $1); if ($1 != "lo") print $1 }' /proc/net/dev | tr '\n' ' ')
if [[ -n "$others" ]]; then
  echo "run_session: refusing to run: network interfaces other than lo are visible ($others)." \
       "Run me through scripts/netns_run.sh." >&2
  case "${CI:-}" in ""|0|false|False|FALSE) exit 125 ;; esac
  echo "run_session: CI=${CI}: failing, not skipping" >&2
  exit 1
fi

mkdir -p "$out_dir"
"$@" >"$out_dir/server.out" 2>"$out_dir/server.err" &
server_pid=$!

alongside_pid=""
if [[ -n "$alongside" ]]; then
  bash -c "$alongside" >"$out_dir/alongside.out" 2>&1 &
  alongside_pid=$!
fi

replay_cmd=("$replay" --trajectory "$trajectory" --out "$out_dir/result.csv"
            --summary "$out_dir/summary.json" --start-delay 20)
[[ -n "$max_force" ]] && replay_cmd+=(--max-force "$max_force")
replay_cmd+=("${replay_args[@]}")
set +e
"${replay_cmd[@]}" >"$out_dir/replay.out" 2>"$out_dir/replay.err"
replay_rc=$?
alongside_rc=0
[[ -n "$alongside_pid" ]] && { wait "$alongside_pid"; alongside_rc=$?; }

server_problem=""
if kill -0 "$server_pid" 2>/dev/null; then
  kill -INT "$server_pid"
  for _ in $(seq 100); do kill -0 "$server_pid" 2>/dev/null || break; sleep 0.1; done
  if kill -0 "$server_pid" 2>/dev/null; then
    kill -KILL "$server_pid"
    server_problem="did not exit within 10 s of SIGINT (killed)"
  fi
  wait "$server_pid"; server_rc=$?
else
  wait "$server_pid"; server_rc=$?
  server_problem="exited before the replay finished (exit code $server_rc)"
fi
set -e
[[ -z "$server_problem" && $server_rc -ne 0 ]] && server_problem="exit code $server_rc after SIGINT"

cat "$out_dir/replay.out"
[[ -s "$out_dir/replay.err" ]] && sed 's/^/replay stderr: /' "$out_dir/replay.err" | tail -n 20
server_line=$(grep -v '^[[:space:]]*$' "$out_dir/server.out" | tail -n 1 || true)
echo "server: ${server_line:-<no summary line on stdout>}"
if [[ -n "$alongside" ]]; then
  echo "alongside: $(tail -n 1 "$out_dir/alongside.out" 2>/dev/null) (exit $alongside_rc)"
fi

if [[ -n "$server_problem" ]]; then
  echo "run_session: server $server_problem; last lines of its stderr:" >&2
  tail -n 20 "$out_dir/server.err" >&2
  exit 2
fi
((replay_rc == 0)) || { echo "run_session: probe_replay failed (exit $replay_rc)" >&2; exit 1; }
((alongside_rc == 0)) || { echo "run_session: --alongside command failed (exit $alongside_rc)" >&2; exit 4; }
exit 0
