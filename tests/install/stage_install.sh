#!/usr/bin/env bash
# Installs the build into a fresh staging prefix (cmake --install) and checks
# that every promised piece is there: programs, pd_core library and headers,
# generated LCM headers and .lcm files, scenes and device profiles, examples,
# the exported CMake package with its namespaced targets.
#   stage_install.sh BUILD_DIR STAGE_DIR
set -euo pipefail
build="$1" stage="$2"
fail() { echo "stage_install: FAIL: $1" >&2; exit 1; }
rm -rf "$stage"
cmake --install "$build" --prefix "$stage" >"$stage.log" 2>&1 || { cat "$stage.log"; fail "cmake --install failed"; }

share="$stage/share/polydepth_haptics"
for f in bin/haptic_server bin/pd_query bin/probe_replay bin/probe_sim bin/probe_recorder \
         bin/echo_server bin/session_viewer lib/libpd_core.a \
         include/pd_core/polydepth/polydepth.h include/pd_core/mesh/load_mesh.h include/pd_core/geometry/pose.h \
         include/haptics_msgs/probe_pose_t.hpp include/haptics_msgs/wrench_t.hpp include/haptics_msgs/sender_identity.h \
         include/haptics_msgs/server_status_t.hpp \
         share/polydepth_haptics/lcm/probe_pose_t.lcm share/polydepth_haptics/lcm/wrench_t.lcm \
         share/polydepth_haptics/config/box_on_box.yaml \
         share/polydepth_haptics/config/devices/sigma7.yaml \
         share/polydepth_haptics/config/meshes/hex_prism.obj \
         share/polydepth_haptics/scripts/netns_run.sh \
         share/polydepth_haptics/examples/pd_core/pd_two_meshes.cc \
         share/polydepth_haptics/examples/probes/probe_client.cc \
         lib/cmake/PolyDepthHaptics/PolyDepthHapticsConfig.cmake \
         lib/cmake/PolyDepthHaptics/PolyDepthHapticsConfigVersion.cmake \
         lib/cmake/PolyDepthHaptics/PolyDepthHapticsTargets.cmake; do
  [[ -e "$stage/$f" ]] || fail "missing $stage/$f"
done
for x in bin/haptic_server bin/probe_replay bin/session_viewer; do
  [[ -x "$stage/$x" ]] || fail "$stage/$x is not executable"
done
# Every .lcm of the source is installed, with a generated header for each.
for lcm in "$(dirname "$0")"/../../msgs/*.lcm; do
  t=$(basename "$lcm" .lcm)
  cmp -s "$lcm" "$share/lcm/$t.lcm" || fail "$share/lcm/$t.lcm differs from msgs/$t.lcm"
  [[ -s "$stage/include/haptics_msgs/$t.hpp" ]] || fail "no generated header for $t"
done
targets="$stage/lib/cmake/PolyDepthHaptics/PolyDepthHapticsTargets.cmake"
grep -q 'add_library(pdh::pd_core ' "$targets" || fail "pdh::pd_core not exported"
grep -q 'add_library(pdh::msgs ' "$targets" || fail "pdh::msgs not exported"
# Nothing may point back into the source or build tree.
src="$(cd "$(dirname "$0")/../.." && pwd)"
if grep -rqF -e "$src" -e "$(cd "$build" && pwd)" "$stage/lib/cmake"; then
  fail "the package config refers to the source or build tree"
fi
# The installed server starts from the installed scene (no network: --check).
"$stage/bin/haptic_server" --config "$share/config/box_on_box.yaml" --check >"$stage.check.log" 2>&1 ||
  { cat "$stage.check.log"; fail "installed haptic_server --check on the installed scene failed"; }
echo "stage_install: PASS ($(find "$stage" -type f | wc -l) files under $stage)"
