#!/usr/bin/env bash
# Inside a private network namespace (scripts/netns_run.sh): starts the
# STAGED haptic_server on the staged box_on_box scene, runs the probe_client
# example against it and checks the wrenches it printed. Reference from the
# scene's gains: the hand feels the coupling (1000 N/m) and the contact
# (3000 N/m) in series, 750 N/m, so pressing the device 5 mm into the table
# gives Fz = 3.75 N up, with the tool itself 5 * 1000 / 4000 = 1.25 mm deep;
# hovering 5 mm above it gives no force. Every pose must be answered or
# overtaken by a newer one (a late client bursts; the server renders the newest).
#   run_probe_client.sh STAGE_DIR CLIENT_BIN WORK_DIR
set -euo pipefail
stage="$1" client="$2" work="$3"
fail() { echo "run_probe_client: FAIL: $1" >&2; exit 1; }
others=$(awk -F: 'NR > 2 { gsub(/ /, "", $1); if ($1 != "lo") print $1 }' /proc/net/dev | tr '\n' ' ')
[[ -z "$others" ]] || { echo "run_probe_client: not in a private network namespace ($others)" >&2; exit 125; }
rm -rf "$work" && mkdir -p "$work"
"$stage/bin/haptic_server" --config "$stage/share/polydepth_haptics/config/box_on_box.yaml" \
  >"$work/server.out" 2>"$work/server.err" &
server=$!
set +e
"$client" >"$work/client.out" 2>"$work/client.err"
rc=$?
kill -INT "$server"; wait "$server"; server_rc=$?
set -e
cat "$work/client.out"
((rc == 0)) || { cat "$work/client.err"; fail "probe_client exited $rc"; }
((server_rc == 0)) || { tail -n 20 "$work/server.err"; fail "haptic_server exited $server_rc"; }
awk '
  /^pose / { seq = $2; fx = $4; fy = $5; fz = $6; depth = $14; n++
             if (seq < 1100 && (fx*fx + fy*fy + fz*fz > 0.05^2)) { print "force while hovering: " $0; bad = 1 }
             if (seq >= 2300 && seq <= 2600) { pressed++
               if (fz < 3.0 || fz > 4.5) { print "Fz not ~3.75 N while pressed 5 mm: " $0; bad = 1 }
               if (fx*fx + fy*fy > 0.2^2) { print "sideways force on a flat press: " $0; bad = 1 }
               if (depth < 0.9 || depth > 1.6) { print "tool depth not ~1.25 mm: " $0; bad = 1 } } }
  /^sent / { sent = $2; answered = $4; superseded = $6 }
  END { if (n < 30) { print "only " n " wrench lines"; bad = 1 }
        if (pressed < 3) { print "no answers while pressed"; bad = 1 }
        # Every pose is rendered or overtaken by a newer one (a client
        # descheduled under load sends bursts; the server renders the newest):
        # none may go missing, and most must be rendered.
        if (sent != 4000 || answered + superseded < sent - 2) {
          print "answered " answered " + superseded " superseded " of " sent; bad = 1 }
        if (answered < 0.5 * sent) { print "answered only " answered " of " sent; bad = 1 }
        exit bad }' "$work/client.out" || fail "wrenches differ from the scene's physics (see above)"
echo "run_probe_client: PASS"
