#!/usr/bin/env bash
# Builds pd_core/examples and probes/examples out of tree against the staged
# install only (find_package(PolyDepthHaptics) from STAGE_DIR), and checks
# that the compiler saw the staged headers, not the source tree's.
#   build_examples.sh SOURCE_DIR STAGE_DIR WORK_DIR [CXX_FLAGS]
# CXX_FLAGS: for a sanitizer build (PD_SANITIZE), whose static pd_core needs
# the same -fsanitize flags in its clients.
set -euo pipefail
src="$1" stage="$2" work="$3" cxx_flags="${4:-}"
fail() { echo "build_examples: FAIL: $1" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
for ex in pd_core probes; do
  cmake -S "$src/$ex/examples" -B "$work/$ex" -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_PREFIX_PATH="$stage" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF \
        -DCMAKE_EXPORT_COMPILE_COMMANDS=ON -DCMAKE_CXX_FLAGS="$cxx_flags" >"$work/$ex.configure.log" 2>&1 ||
    { cat "$work/$ex.configure.log"; fail "configuring $ex/examples against $stage failed"; }
  grep -q "PolyDepthHaptics_DIR:PATH=$stage/lib/cmake/PolyDepthHaptics" "$work/$ex/CMakeCache.txt" ||
    fail "$ex/examples did not find the package in $stage"
  cmake --build "$work/$ex" -j2 >"$work/$ex.build.log" 2>&1 ||
    { cat "$work/$ex.build.log"; fail "building $ex/examples failed"; }
  # Headers from the stage, never from the repository.
  cc="$work/$ex/compile_commands.json"
  grep -q -- "-isystem $stage/include\|-I$stage/include" "$cc" || fail "$ex: $stage/include not on the include path"
  # Every include directory outside the stage must be outside the repository.
  grep -Eo -- '(-I|-isystem )[^ ]+' "$cc" | sed -E 's/^(-I|-isystem )//' | sort -u | while read -r dir; do
    [[ "$dir" == "$stage"/* || "$dir" != "$src"/* ]] || fail "$ex: compiled against $dir (repository)"
  done
done
[[ -x "$work/pd_core/pd_two_meshes" ]] || fail "pd_two_meshes not built"
[[ -x "$work/probes/probe_client" ]] || fail "probe_client not built"
echo "build_examples: PASS (pd_two_meshes, probe_client built against $stage)"
