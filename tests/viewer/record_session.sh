#!/usr/bin/env bash
# Inside a private network namespace: a 5 s box_on_box session (one press
# into the table) of the real haptic_server and probe_replay, recorded twice:
# probe_replay's result CSV (+ its session plot) and an LCM log of poses and
# wrenches by probe_recorder. Then checks the plot by its pixels: the right
# size, and each of the five panels' curve colours present.
#   record_session.sh ROOT BIN_DIR PNG_STATS WORK_DIR
set -euo pipefail
root="$1" bin="$2" png_stats="$3" work="$4"
fail() { echo "record_session: FAIL: $1" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
head -n 5001 "$root/probes/trajectories/box_on_box.csv" >"$work/trajectory.csv"
"$root/probes/scripts/run_session.sh" --out-dir "$work" --replay "$bin/probe_replay" \
  --trajectory "$work/trajectory.csv" --replay-arg --max-superseded --replay-arg 0.2 \
  --alongside "'$bin/probe_recorder' --out '$work/session.lcm' --duration 7" \
  -- "$bin/haptic_server" --config "$root/config/box_on_box.yaml"
[[ -s "$work/result.csv" && -s "$work/session.lcm" ]] || fail "no result.csv or session.lcm"
grep -qxF "session plot: $work/result.png" "$work/replay.out" || fail "probe_replay did not print its plot path"

# The plot: 1100 x 1250, mostly white, and every panel's curve drawn.
"$png_stats" "$work/result.png" force=d62728 torque=9467bd depth=1f77b4 contacts=2ca02c \
  round_trip=ff7f0e | tee "$work/result.png.stats"
awk '
  $1 == "size" && !($2 == 1100 && $3 == 1250) { print "size " $2 "x" $3 ", expected 1100x1250"; bad = 1 }
  $1 == "background" && $2 != "ffffff" { print "background " $2 ", expected white"; bad = 1 }
  $1 == "hue" && $3 < 0.0003 { print "no " $2 " curve (" $3 " of the pixels)"; bad = 1 }
  $1 == "hue" { hues++ }
  END { if (hues != 5) { print "png_stats gave " hues " hues"; bad = 1 } exit bad }' "$work/result.png.stats" ||
  fail "$work/result.png does not show the five panels"
echo "record_session: PASS ($(($(wc -l <"$work/result.csv") - 1)) poses; plot $work/result.png)"
