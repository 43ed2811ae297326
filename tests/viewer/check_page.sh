#!/usr/bin/env bash
# Opens a session page in Debian's headless Chromium (WebGL on the software
# path) and checks: no console error, warning or uncaught exception; the page
# reports ready with the expected frame count; playing advances the frame at
# least 3 times; and the screenshot shows the meshes: scene-blue and
# tool-orange pixels (by hue, see png_stats) each cover a visible part of it.
#   check_page.sh PAGE PNG_STATS WORK_DIR MIN_FRAMES
set -euo pipefail
page="$1" png_stats="$2" work="$3" min_frames="$4"
fail() { echo "check_page: FAIL: $1" >&2; exit 1; }
mkdir -p "$work"
command -v chromium >/dev/null || fail "chromium not installed (scripts/install_deps.sh)"
shot="$work/screenshot.png" log="$work/chromium.log"
rm -f "$shot"
# A fresh profile each run; virtual time lets the page play a few seconds of session.
timeout 120 chromium --headless --no-sandbox --disable-gpu --enable-unsafe-swiftshader \
  --user-data-dir="$work/profile" --window-size=1280,800 --enable-logging=stderr --v=0 \
  --virtual-time-budget=10000 --screenshot="$shot" "file://$(realpath "$page")" >"$log" 2>&1 ||
  { tail -n 20 "$log"; fail "chromium failed"; }
grep -F ':CONSOLE' "$log" | sed 's/^.*:CONSOLE[^]]*\] //' >"$work/console.txt" || true
cat "$work/console.txt"
if grep -Eq 'console\.error:|console\.warn:|Uncaught' "$work/console.txt"; then
  fail "console errors or warnings (above)"
fi
ready=$(grep -Eo 'viewer: ready frames=[0-9]+ objects=[0-9]+ webgl=1' "$work/console.txt" || true)
[[ -n "$ready" ]] || fail "the page never reported ready with a WebGL context"
frames=$(sed -E 's/.*frames=([0-9]+).*/\1/' <<<"$ready")
((frames >= min_frames)) || fail "only $frames frames in the page (expected >= $min_frames)"
grep -Eo 'viewer: frame [0-9]+' "$work/console.txt" | awk '{ print $3 }' >"$work/frames.txt"
awk 'NR > 1 && $1 > prev { up++ } NR > 1 && $1 < prev { down++ } { prev = $1 }
     END { if (up < 3 || down > 0) { print "frames advanced " up + 0 " times, went back " down + 0 " times"; exit 1 } }' \
  "$work/frames.txt" || fail "playback did not advance"

[[ -s "$shot" ]] || fail "no screenshot"
"$png_stats" "$shot" scene=4a90d9 tool=e8902a | tee "$work/screenshot.stats"
awk '
  $1 == "size" && !($2 == 1280 && $3 == 800) { print "size " $2 "x" $3; bad = 1 }
  $1 == "hue" && $2 == "scene" && $3 < 0.02 { print "scene meshes cover only " $3; bad = 1 }
  $1 == "hue" && $2 == "tool" && $3 < 0.001 { print "tool covers only " $3; bad = 1 }
  END { exit bad }' "$work/screenshot.stats" || fail "the screenshot does not show the meshes"
echo "check_page: PASS ($frames frames, $(wc -l <"$work/frames.txt") frame reports, screenshot $shot)"
