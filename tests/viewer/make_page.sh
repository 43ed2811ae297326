#!/usr/bin/env bash
# Turns the recorded session (result CSV or LCM log) into a page with
# session_viewer, checks what it reports (every pose read, the recomputed
# force close to the recorded one) and opens the page (check_page.sh).
#   make_page.sh VIEWER SCENE SESSION PNG_STATS WORK_DIR MIN_POSES MAX_POSES
# (An LCM log may miss a few poses: the recorder is an ordinary UDP listener.)
set -euo pipefail
viewer="$1" scene="$2" session="$3" png_stats="$4" work="$5" min_poses="$6" max_poses="$7"
fail() { echo "make_page: FAIL: $1" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
"$viewer" --scene "$scene" --session "$session" --out "$work/session.html" | tee "$work/viewer.out" ||
  fail "session_viewer failed"
poses=$(sed -nE "s|^session_viewer: $session \(([0-9]+) poses, [0-9]+ answered\).*|\1|p" "$work/viewer.out")
[[ -n "$poses" ]] && ((poses >= min_poses && poses <= max_poses)) ||
  fail "read ${poses:-no} poses from $session, expected $min_poses..$max_poses"
# The simulated tool is recomputed offline from the device poses: its force
# must match the recorded one (the same renderer on the same poses; the live
# loop's tick phase differs by < 1 ms): median within 2% of the peak force.
awk '/recomputed vs recorded force/ {
       med = $7; peak = $(NF - 1); sub(/\(/, "", peak)
       if (peak < 1) { print "peak recorded force " peak " N: no contact in the session?"; exit 1 }
       if (med > 0.02 * peak) { print "median difference " med " N of peak " peak " N"; exit 1 }
       found = 1 }
     END { exit !found }' "$work/viewer.out" || fail "recomputed force differs from the recorded one"
size=$(stat -c %s "$work/session.html")
((size > 800000)) || fail "page of $size bytes cannot hold three.js"
if grep -Eq '<script[^>]+src=|https?://[^" ]*\.js' "$work/session.html"; then
  fail "the page loads scripts from elsewhere (must be self-contained)"
fi
"$(dirname "$0")/check_page.sh" "$work/session.html" "$png_stats" "$work/browser" 50
