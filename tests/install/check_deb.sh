#!/usr/bin/env bash
# Builds the Debian package with CPack and checks its contents and metadata.
#   check_deb.sh BUILD_DIR WORK_DIR CPU_LEVEL
# CPU_LEVEL: the x86-64 level the build resolved (scripts/cmake/cpu_level.cmake);
# a package built for x86-64-v3 says so in its description.
set -euo pipefail
build="$1" work="$2" level="$3"
fail() { echo "check_deb: FAIL: $1" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
cpack --config "$build/CPackConfig.cmake" -G DEB -B "$work" >"$work/cpack.log" 2>&1 ||
  { cat "$work/cpack.log"; fail "cpack -G DEB failed"; }
deb=$(ls "$work"/polydepth-haptics_*.deb 2>/dev/null | head -n 1)
[[ -n "$deb" ]] || fail "no polydepth-haptics_*.deb in $work"
dpkg-deb -c "$deb" | awk '{ print $6 }' >"$work/contents.txt"
for f in ./usr/bin/haptic_server ./usr/bin/probe_replay ./usr/bin/session_viewer ./usr/bin/pd_query \
         ./usr/lib/libpd_core.a ./usr/include/pd_core/polydepth/polydepth.h ./usr/include/haptics_msgs/wrench_t.hpp \
         ./usr/share/polydepth_haptics/lcm/probe_pose_t.lcm \
         ./usr/share/polydepth_haptics/config/devices/sigma7.yaml \
         ./usr/lib/cmake/PolyDepthHaptics/PolyDepthHapticsConfig.cmake; do
  grep -qxF "$f" "$work/contents.txt" || fail "$f not in $deb"
done
[[ "$(dpkg-deb -f "$deb" Package)" == polydepth-haptics ]] || fail "wrong package name"
depends=$(dpkg-deb -f "$deb" Depends)
for d in libeigen3-dev liblcm-dev libjs-three libassimp5 liblcm1; do
  grep -q "$d" <<<"$depends" || fail "Depends lacks $d: $depends"
done
description=$(dpkg-deb -f "$deb" Description)
if [[ "$level" == "x86-64-v3" ]]; then
  grep -q "x86-64-v3" <<<"$description" || fail "built for x86-64-v3 but the description does not say so: $description"
else
  ! grep -q "x86-64-v3" <<<"$description" || fail "built for $level but the description says x86-64-v3: $description"
fi
echo "check_deb: PASS ($(basename "$deb"), $(wc -l <"$work/contents.txt") entries, Depends: $depends)"
