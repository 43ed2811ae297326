#!/usr/bin/env bash
# session_viewer refuses bad input with exit 1 and a message naming the
# culprit, and writes no page.
#   bad_input.sh VIEWER SCENE TRAJECTORY_CSV WORK_DIR
set -euo pipefail
viewer="$1" scene="$2" trajectory="$3" work="$4"
fail() { echo "bad_input: FAIL: $1" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
expect() {  # expect NAME PATTERN ARGS...: exit 1, stderr matching PATTERN, no page
  local name="$1" pattern="$2"; shift 2
  set +e; "$viewer" "$@" --out "$work/$name.html" 2>"$work/$name.err" >/dev/null; local rc=$?; set -e
  ((rc == 1)) || fail "$name: exit $rc, expected 1"
  grep -q -- "$pattern" "$work/$name.err" || { cat "$work/$name.err"; fail "$name: message lacks '$pattern'"; }
  [[ ! -s "$work/$name.html" ]] || fail "$name: wrote a page anyway"
  echo "bad_input: $name: $(head -n 1 "$work/$name.err")"
}
expect missing_session "$work/none.csv" --scene "$scene" --session "$work/none.csv"
expect trajectory_not_session "header must be" --scene "$scene" --session "$trajectory"
printf 'seq,t,send_utime,x,y,z,qw,qx,qy,qz,answered,answers,fx,fy,fz,tx,ty,tz,flags,penetration_depth,contact_count,latency_us\n0,0,5,0,0,0.04,1,0,0,0,1,1,nan,0,0,0,0,0,0,0,0,100\n' >"$work/nan.csv"
expect nan_force "nan.csv:2: field 'fx'" --scene "$scene" --session "$work/nan.csv"
expect missing_scene "$work/none.yaml" --scene "$work/none.yaml" --session "$trajectory"
head -n 3 "$work/nan.csv" | sed 's/nan/1/' >"$work/ok.csv"
expect no_three_js "libjs-three" --scene "$scene" --session "$work/ok.csv" --three-dir "$work/no_three"
echo "bad_input: PASS"
