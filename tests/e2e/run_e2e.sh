#!/usr/bin/env bash
# End-to-end test driver, run by CTest through scripts/netns_run.sh (so it is
# already inside a private network namespace). Starts a server and
# probe_replay as separate processes over LCM udpm, replays a committed
# trajectory, then checks the per-pose results against
# tests/e2e/expect/<expect>.yaml with check_contact.
#
#   run_e2e.sh --server haptic|echo --scene NAME --bin-dir DIR --work DIR
#              [--expect NAME] [--bad-input]
#
# --server haptic runs build/bin/haptic_server --config config/NAME.yaml;
# --server echo runs echo_server (transport only, zero wrenches).
# --bad-input sends garbage and wrong-type messages to the pose channel
# during the replay and also requires the server's status to count them.
#
# Unanswered poses: none may be lost at the end, and every unanswered pose
# must be accounted for by the server's own exit summary:
#   unanswered == dropped + (sent - received)
# echo_server answers every pose it receives (dropped = 0), so only poses
# lost on the way (UDP under heavy load) may go unanswered, at most 1 %.
# haptic_server renders at a fixed rate from the newest pose, so when two
# poses arrive within one tick it drops the older (poses_dropped); up to
# MAX_SUPERSEDED (default 0.2) of the poses may go unanswered that way.
# The haptic server's contact model must never go stale (model_stale_ticks).
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"

server="" scene="" bin="" work="" expect="" bad_input=0
while (($#)); do
  case "$1" in
    --server) server="$2"; shift 2 ;;
    --scene) scene="$2"; shift 2 ;;
    --bin-dir) bin="$2"; shift 2 ;;
    --work) work="$2"; shift 2 ;;
    --expect) expect="$2"; shift 2 ;;
    --bad-input) bad_input=1; shift ;;
    *) echo "run_e2e: unknown option '$1'" >&2; exit 3 ;;
  esac
done
[[ -n "$server" && -n "$scene" && -n "$bin" && -n "$work" ]] || { echo "run_e2e: missing options" >&2; exit 3; }
expect="${expect:-$scene}"
trajectory="$ROOT/probes/trajectories/$scene.csv"
expect_file="$HERE/expect/$expect.yaml"
rm -rf "$work"
mkdir -p "$work"

replay_args=(--replay-arg --realtime)  # SCHED_FIFO sender: fewer stalls and bursts
case "$server" in
  haptic)
    server_cmd=("$bin/haptic_server" --config "$ROOT/config/$scene.yaml")
    # PD_E2E_TIMING_RELAXED (scripts/test_sanitize.sh): a sanitized build of
    # the PolyDepth scenes cannot tick at 1 kHz, so superseded poses are
    # tolerated there; everything else is still checked.
    default_superseded=0.2
    [[ -n "${PD_E2E_TIMING_RELAXED:-}" ]] && default_superseded=0.98
    replay_args+=(--replay-arg --max-superseded --replay-arg "${MAX_SUPERSEDED:-$default_superseded}") ;;
  echo)
    server_cmd=("$bin/echo_server")
    replay_args+=(--replay-arg --max-superseded --replay-arg 0.01) ;;
  *) echo "run_e2e: --server must be haptic or echo" >&2; exit 3 ;;
esac

session=("$ROOT/probes/scripts/run_session.sh" --out-dir "$work" --replay "$bin/probe_replay"
         --trajectory "$trajectory" "${replay_args[@]}")
if ((bad_input)); then
  # Starts after the server is up and the replay is under way; ~3 s of abuse.
  session+=(--alongside "'$bin/bad_input_sender' --start-delay 3 --rounds 300 --interval-ms 10")
fi

echo "run_e2e: ${server_cmd[*]} <- $(basename "$trajectory"), expectations $(basename "$expect_file")"
"${session[@]}" -- "${server_cmd[@]}"

"$bin/check_contact" "$work/result.csv" "$expect_file"

# Every unanswered pose must be one the server says it dropped or never got.
json_int() { grep -o "\"$1\": [0-9]*" "$work/summary.json" | grep -o '[0-9]*$'; }
sent=$(json_int poses_sent) unanswered=$(json_int unanswered)
line=$(tail -n 1 "$work/server.out")
if [[ "$server" == haptic ]]; then
  received=$(grep -o 'poses_received=[0-9]*' <<<"$line" | cut -d= -f2 || true)
  dropped=$(grep -o 'poses_dropped=[0-9]*' <<<"$line" | cut -d= -f2 || true)
else
  received=$(grep -o 'poses received [0-9]*' <<<"$line" | grep -o '[0-9]*$' || true)
  dropped=0
fi
[[ -n "$received" && -n "$dropped" ]] || { echo "run_e2e: FAIL: no poses received/dropped counts in the server's last line: $line" >&2; exit 1; }
accounted=$((dropped + sent - received))
# A wrench lost on its way back (the replay counts gaps in the server's tick
# seq) can leave its pose unanswered too: at most one pose per lost wrench.
missed=$(json_int wrenches_missed)
missed=${missed:-0}
echo "run_e2e: unanswered $unanswered of $sent; server dropped $dropped, never received $((sent - received)); wrenches lost in transport $missed"
if ((unanswered < accounted || unanswered > accounted + missed)); then
  echo "run_e2e: FAIL: $unanswered unanswered poses but the server accounts for $accounted" >&2
  exit 1
fi

# The contact model must never go stale (contact.model_max_age_ms): a stale
# model ramps the contact out, and the wall goes soft. The replay sends at
# SCHED_FIFO, but only while sending, so its summaries and plot do not
# starve the server's normal-priority geometry thread after the session.
# (Not under PD_E2E_TIMING_RELAXED: a sanitized PolyDepth query is that slow.)
if [[ "$server" == haptic && -z "${PD_E2E_TIMING_RELAXED:-}" ]]; then
  stale=$(grep -o 'model_stale_ticks=[0-9]*' <<<"$line" | cut -d= -f2 || true)
  age_max=$(grep -o 'model_age_max_ticks=[0-9]*' <<<"$line" | cut -d= -f2 || true)
  [[ -n "$stale" ]] || { echo "run_e2e: FAIL: no model_stale_ticks in the server's last line: $line" >&2; exit 1; }
  echo "run_e2e: contact model: stale ticks $stale, oldest ${age_max:-?} ticks"
  if ((stale > 0)); then
    echo "run_e2e: FAIL: the contact model was stale on $stale ticks (geometry thread starved or stuck)" >&2
    exit 1
  fi
fi

if ((bad_input)); then
  bad_sent=$(grep -o 'undecodable_on_channel=[0-9]*' "$work/alongside.out" | cut -d= -f2)
  malformed=$(json_int messages_malformed || true)
  echo "run_e2e: bad input: $bad_sent undecodable messages sent, server status messages_malformed=${malformed:-<no status>}"
  if [[ -z "$malformed" || "$malformed" -eq 0 ]]; then
    echo "run_e2e: FAIL: the server's status does not count the undecodable pose-channel messages" >&2
    exit 1
  fi
fi
echo "run_e2e: PASS"
