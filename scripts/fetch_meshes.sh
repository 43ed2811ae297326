#!/usr/bin/env bash
# Extracts the real meshes used by tests and benchmarks from Debian's libcgal-demo
# (data.tar.gz) into build/meshes/. Nothing large is committed.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
OUT="${1:-$ROOT/build/meshes}"
TAR=/usr/share/doc/libcgal-dev/data.tar.gz
MESHES=(knot1.off cow.off camel.off bunny00.off armadillo.off ChineseDragon-10kv.off mushroom.off fandisk.off bull.off refined_elephant.off bones.off
        elephant.off dino.off femur.off homer.off triceratops.off elk.off hand.off anchor_dense.off knot.off
        couplingdown.off rotor_small.off blobby.off)
[[ -f "$TAR" ]] || { echo "fetch_meshes: $TAR missing (apt-get install libcgal-demo)" >&2; exit 1; }
mkdir -p "$OUT"
need=()
for m in "${MESHES[@]}"; do [[ -s "$OUT/$m" ]] || need+=("data/meshes/$m"); done
if ((${#need[@]})); then
  tar -xzf "$TAR" -C "$OUT" --strip-components=2 "${need[@]}"
fi
echo "fetch_meshes: ${#MESHES[@]} meshes in $OUT"
