#!/usr/bin/env bash
# Installs dependencies, builds, extracts test meshes and runs the whole test suite through CTest.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
"$ROOT/scripts/install_deps.sh"
"$ROOT/scripts/build.sh"
"$ROOT/scripts/fetch_meshes.sh"
cd "$ROOT/build"
# The tests get a private scratch directory as TMPDIR (and GoogleTest's
# TEST_TMPDIR) and must leave it empty: a test that leaves files behind
# fails the run, naming them.
scratch="$(mktemp -d "${TMPDIR:-/tmp}/pd_tests.XXXXXX")"
trap 'rm -rf "$scratch"' EXIT
status=0
TMPDIR="$scratch" TEST_TMPDIR="$scratch/" ctest --output-on-failure -j"$(nproc)" --timeout 900 || status=$?
leftovers="$(find "$scratch" -mindepth 1 -maxdepth 1 -printf '  %f\n')"
if [[ -n "$leftovers" ]]; then
  echo "test.sh: the tests left these behind in their TMPDIR:" >&2
  echo "$leftovers" >&2
  [[ $status -ne 0 ]] || status=1
fi
exit "$status"
