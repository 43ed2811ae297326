#!/usr/bin/env bash
# Regenerates the committed trajectories probes/trajectories/<scene>.csv from
# their parameter files <scene>.params.yaml with probe_sim (no network: CSV
# only). Usage: probes/scripts/make_trajectories.sh [BIN_DIR] (default build/bin).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BIN="${1:-$ROOT/build/bin}"
[[ -x "$BIN/probe_sim" ]] || { echo "make_trajectories: $BIN/probe_sim missing: build first" >&2; exit 1; }
for params in "$ROOT"/probes/trajectories/*.params.yaml; do
  "$BIN/probe_sim" --params "$params" --csv-out "${params%.params.yaml}.csv"
done
