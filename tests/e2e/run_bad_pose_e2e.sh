#!/usr/bin/env bash
# End-to-end bad pose input, run by CTest through scripts/netns_run.sh (so it
# is inside a private network namespace): starts haptic_server on
# config/box_on_box.yaml, drives it with bad_pose_check (bad values, order
# anomalies, a 10x burst, malformed messages), then stops the server with
# SIGINT and requires a clean exit and its summary line.
#   run_bad_pose_e2e.sh BIN_DIR WORK_DIR [PHASE_SECONDS]
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
bin="$1" work="$2" phase="${3:-1}"
rm -rf "$work" && mkdir -p "$work"
"$bin/haptic_server" --config "$ROOT/config/box_on_box.yaml" >"$work/server.out" 2>"$work/server.err" &
server=$!
set +e
# PD_E2E_TIMING_RELAXED (scripts/test_sanitize.sh): real-time expectations off.
relaxed=()
[[ -n "${PD_E2E_TIMING_RELAXED:-}" ]] && relaxed=(--allow-watchdog-trips)
"$bin/bad_pose_check" --phase-seconds "$phase" "${relaxed[@]}" | tee "$work/check.out"
check=${PIPESTATUS[0]}
alive=0
kill -0 "$server" 2>/dev/null && alive=1
kill -INT "$server" 2>/dev/null
wait "$server"
server_rc=$?
set -e
echo "run_bad_pose_e2e: $(tail -n 1 "$work/server.out")"
if ((alive == 0)); then
  echo "run_bad_pose_e2e: FAIL: the server died during the run (exit $server_rc); stderr tail:"
  tail -n 20 "$work/server.err"
  exit 1
fi
if ((server_rc != 0)); then
  echo "run_bad_pose_e2e: FAIL: the server exited $server_rc on SIGINT"; tail -n 20 "$work/server.err"; exit 1
fi
grep -q '^haptic_server summary: .*poses_out_of_order=[1-9]' "$work/server.out" ||
  { echo "run_bad_pose_e2e: FAIL: no summary line counting out-of-order poses"; exit 1; }
((check == 0)) || { echo "run_bad_pose_e2e: FAIL (bad_pose_check exit $check)"; exit 1; }
echo "run_bad_pose_e2e: PASS"
