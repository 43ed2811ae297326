#!/usr/bin/env bash
# Installs dependencies, builds, extracts test meshes and runs the whole test suite through CTest.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
"$ROOT/scripts/install_deps.sh"
"$ROOT/scripts/build.sh"
"$ROOT/scripts/fetch_meshes.sh"
cd "$ROOT/build"
ctest --output-on-failure -j"$(nproc)" --timeout 900
