#!/usr/bin/env bash
# Configures and builds the project in Release into build/ (executables in build/bin/).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
cd "$ROOT"
cmake -S . -B build -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" ${CMAKE_EXTRA_ARGS:-} >/dev/null
cmake --build build -j"$(nproc)"
