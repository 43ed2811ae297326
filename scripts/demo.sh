#!/usr/bin/env bash
# Demo of the whole loop on one machine: in one private network namespace
# (scripts/netns_run.sh; nothing leaves the machine), start haptic_server on
# a scene, play the scene's recorded probe trajectory to it with
# probe_replay, stop the server, and print what happened: poses sent and
# answered, round-trip latency p50/p99/max, max force, the server's status
# (deadline misses, ...) and the server's own summary line.
#
#   scripts/demo.sh [SCENE]                 SCENE: knot_on_bunny (default: a 6.4k-triangle knot tool
#                                           slid over a 75k-triangle bunny, PolyDepth), box_on_box,
#                                           spoon_in_cup, peg_in_hole
#   scripts/demo.sh CONFIG.yaml [TRAJECTORY]
#
# Needs a build (scripts/build.sh; BUILD_DIR overrides build/). Results are
# kept in DEMO_OUT (default: a new /tmp/haptics_demo.* directory).
# Exit code: non-zero if the server failed or a pose went unanswered (see
# probes/scripts/run_session.sh for the codes), 5 if only the session page
# (session_viewer) failed. Besides result.csv the run leaves result.png (the
# session plot) and session.html (the browser viewer) in the results directory.
# One exception, by design of the server: it renders at a fixed rate from the
# newest pose, so a pose that arrives in the same tick as the next one is
# superseded (the server counts it in poses_dropped). Up to MAX_SUPERSEDED (default 0.2) of the poses may
# be superseded; MAX_SUPERSEDED=0 demands an answer to every pose.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BIN="${BUILD_DIR:-$ROOT/build}/bin"

arg="${1:-knot_on_bunny}"
if [[ "$arg" == *.yaml || "$arg" == */* ]]; then
  config="$arg"
  scene="$(basename "$arg" .yaml)"
else
  config="$ROOT/config/$arg.yaml"
  scene="$arg"
fi
trajectory="${2:-$ROOT/probes/trajectories/$scene.csv}"

if [[ ! -f "$config" ]]; then
  echo "demo: no scene config '$config'. Scenes:" $(cd "$ROOT/config" && ls *.yaml 2>/dev/null | sed 's/\.yaml$//') >&2
  exit 3
fi
if [[ ! -f "$trajectory" ]]; then
  echo "demo: no trajectory '$trajectory' for scene '$scene'; give one as the second argument" >&2
  exit 3
fi
for exe in haptic_server probe_replay; do
  [[ -x "$BIN/$exe" ]] || { echo "demo: $BIN/$exe missing: run scripts/build.sh first" >&2; exit 3; }
done

out="${DEMO_OUT:-$(mktemp -d /tmp/haptics_demo.XXXXXX)}"
poses=$(($(grep -cv '^[[:space:]]*\(#\|$\)' "$trajectory") - 1))
echo "demo: scene '$scene' ($config)"
echo "demo: trajectory $trajectory ($poses poses), results in $out"

set +e
"$ROOT/scripts/netns_run.sh" "$ROOT/probes/scripts/run_session.sh" \
  --out-dir "$out" --replay "$BIN/probe_replay" --trajectory "$trajectory" \
  --replay-arg --realtime --replay-arg --max-superseded --replay-arg "${MAX_SUPERSEDED:-0.2}" \
  -- "$BIN/haptic_server" --config "$config"
rc=$?
set -e
if ((rc == 0)); then
  echo "demo: OK (per-pose results: $out/result.csv, summary: $out/summary.json)"
else
  echo "demo: FAILED (exit $rc); logs in $out" >&2
fi
if [[ -s "$out/result.png" ]]; then
  echo "demo: session plot (|force|, |torque|, depth, contacts, round trip over time): $out/result.png"
fi
# The session in the browser: scene, device and simulated tool, wrench, contacts.
if [[ -s "$out/result.csv" && -x "$BIN/session_viewer" ]]; then
  if "$BIN/session_viewer" --scene "$config" --session "$out/result.csv" --out "$out/session.html" \
       >"$out/viewer.out" 2>&1; then
    echo "demo: session viewer page (open in a browser, works offline): $out/session.html"
  else
    echo "demo: session_viewer failed; see $out/viewer.out" >&2
    ((rc != 0)) || rc=5
  fi
fi
exit "$rc"
