#!/usr/bin/env bash
# scripts/demo.sh on a 3 s box_on_box trajectory (one press): it must print
# the paths of the session plot and the viewer page, and both must hold a
# picture: a plot with curves on it and a page carrying the session.
#   demo_outputs.sh ROOT BUILD_DIR PNG_STATS WORK_DIR
set -euo pipefail
root="$1" build="$2" png_stats="$3" work="$4"
fail() { echo "demo_outputs: FAIL: $1" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
head -n 3001 "$root/probes/trajectories/box_on_box.csv" >"$work/press.csv"
set +e
DEMO_OUT="$work/out" BUILD_DIR="$build" "$root/scripts/demo.sh" "$root/config/box_on_box.yaml" \
  "$work/press.csv" >"$work/demo.out" 2>&1
rc=$?
set -e
cat "$work/demo.out"
((rc != 125)) || exit 125  # no private network namespace here
((rc == 0)) || fail "demo exited $rc"
grep -qxF "demo: session plot (|force|, |torque|, depth, contacts, round trip over time): $work/out/result.png" \
  "$work/demo.out" || fail "demo did not print the plot's path"
grep -qxF "demo: session viewer page (open in a browser, works offline): $work/out/session.html" \
  "$work/demo.out" || fail "demo did not print the page's path"
"$png_stats" "$work/out/result.png" force=d62728 | tee "$work/plot.stats"
awk '$1 == "foreground" && $2 < 0.01 { bad = 1 } $1 == "hue" && $3 < 0.0003 { bad = 1 } END { exit bad }' \
  "$work/plot.stats" || fail "the plot is blank or lacks the force curve"
grep -q '"session_frames":3000' "$work/out/session.html" || fail "the page does not hold the 3000 poses"
echo "demo_outputs: PASS"
