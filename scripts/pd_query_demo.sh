#!/usr/bin/env bash
# Installs, builds and runs pd_query on a default model pair (two torus knots
# from Debian's libcgal-demo), cold and coherent, printing what happened.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
"$ROOT/scripts/install_deps.sh" >/dev/null
"$ROOT/scripts/build.sh" >/dev/null
"$ROOT/scripts/fetch_meshes.sh" >/dev/null
KNOT="$ROOT/build/meshes/knot1.off"
echo "pd_query demo: probe and scene = $KNOT (6400 triangles each), scene at the origin"
echo "probe poses: x y z qw qx qy qz (m, unit quaternion w first), moving through the scene"
poses=$(for i in $(seq 0 20); do
  python3 -c "import math;t=$i/20.0;a=0.4*t;print(f'{-0.5+1.0*t:.4f} 0.05 0.02 {math.cos(a/2):.6f} 0 0 {math.sin(a/2):.6f}')"
done)
echo "--- cold queries (independent) ---"
echo "$poses" | "$ROOT/build/bin/pd_query" "$KNOT" "$KNOT" | python3 -c '
import json,sys
for i,l in enumerate(sys.stdin):
    r=json.loads(l)
    if "error" in r: print(i, "error:", r["error"]); continue
    print(f"{i:2d} collision={r[\"collision\"]!s:5} depth={r[\"depth\"]:.5f} m normal=[{r[\"normal\"][0]:+.3f} {r[\"normal\"][1]:+.3f} {r[\"normal\"][2]:+.3f}] iterations={r[\"iterations\"]:3d} init={r[\"initializer\"]:20s} time={r[\"time_us\"]:9.1f} us")'
echo "--- coherent queries (warm-started like a moving probe) ---"
echo "$poses" | "$ROOT/build/bin/pd_query" --coherent "$KNOT" "$KNOT" | python3 -c '
import json,sys
for i,l in enumerate(sys.stdin):
    r=json.loads(l)
    print(f"{i:2d} collision={r[\"collision\"]!s:5} depth={r[\"depth\"]:.5f} m iterations={r[\"iterations\"]:3d} init={r[\"initializer\"]:20s} time={r[\"time_us\"]:9.1f} us")'
