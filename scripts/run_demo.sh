#!/usr/bin/env bash
# The README's main-job command: installs the Debian packages, builds in
# Release, then runs the haptic server on a built-in default scene with the
# replay tool standing in for the device (inside a private network namespace,
# so no packet leaves the machine) and prints what happened.
#   scripts/run_demo.sh [SCENE]   SCENE: knot_on_bunny (default: CGAL knot1 as a 5 cm mesh tool
#                                 over CGAL bunny00 at 15 cm, solved by PolyDepth), box_on_box,
#                                 spoon_in_cup, peg_in_hole
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
"$ROOT/scripts/install_deps.sh"
"$ROOT/scripts/build.sh"
"$ROOT/scripts/fetch_meshes.sh" >/dev/null  # the default scene's CGAL meshes into build/meshes/
exec "$ROOT/scripts/demo.sh" "$@"
