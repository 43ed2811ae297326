#!/usr/bin/env bash
# Installs dependencies, builds, extracts the benchmark meshes and runs the
# PolyDepth speed-against-error benchmark. Arguments go to bench_pd, e.g.
#   bench/run_pd_bench.sh --quick
# Results: bench/results/pd_speed_error.md (+ CSVs and PNGs beside it).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
"$ROOT/scripts/install_deps.sh"
"$ROOT/scripts/build.sh"
"$ROOT/scripts/fetch_meshes.sh"
cd "$ROOT"
exec "$ROOT/build/bin/bench_pd" --mesh-dir "$ROOT/build/meshes" "$@"
