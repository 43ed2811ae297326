#!/usr/bin/env bash
# The browser check must be able to fail: a page whose three.js throws (a
# stand-in three.min.js) draws nothing and logs an uncaught error, and
# check_page.sh must reject it.
#   check_page_selftest.sh VIEWER SCENE SESSION_CSV PNG_STATS WORK_DIR
set -euo pipefail
viewer="$1" scene="$2" session="$3" png_stats="$4" work="$5"
rm -rf "$work" && mkdir -p "$work/three/examples/js/controls"
echo 'throw new Error("three.js stand-in: broken on purpose");' >"$work/three/three.min.js"
: >"$work/three/examples/js/controls/OrbitControls.js"
"$viewer" --scene "$scene" --session "$session" --out "$work/broken.html" --three-dir "$work/three" >/dev/null
if "$(dirname "$0")/check_page.sh" "$work/broken.html" "$png_stats" "$work/browser" 50 >"$work/check.out" 2>&1; then
  cat "$work/check.out"; echo "check_page_selftest: FAIL: check_page.sh passed a broken page" >&2; exit 1
fi
grep -q 'check_page: FAIL: console errors' "$work/check.out" ||
  { cat "$work/check.out"; echo "check_page_selftest: FAIL: rejected for another reason" >&2; exit 1; }
echo "check_page_selftest: PASS (broken page rejected: $(grep -m1 'console.error' "$work/check.out" | cut -c1-120))"
