#!/usr/bin/env bash
# PD_CPU_LEVEL changes speed, never answers (scripts/cmake/cpu_level.cmake):
# pd_query is built a second time at the other x86-64 level and both builds
# answer the same cold queries and the same coherent path of real-mesh
# poses. Every output field but the timings must match byte for byte:
# depth and translation to the last bit, and the work (box and triangle
# tests), which follows every branch the solver took.
#   same_answers_at_every_cpu_level.sh SOURCE_DIR PD_QUERY LEVEL MESH_DIR WORK_DIR
# LEVEL: the level PD_QUERY was built at. The other build is baseline x86-64
# when PD_QUERY is x86-64-v3, else PD_CPU_LEVEL=auto: x86-64-v3 where this
# machine can run it (cpu_level.cmake decides, as for the main build), the
# same level again where it cannot (then only the build's reproducibility is
# checked, said in the output).
set -euo pipefail
src="$1" pd_query="$2" level="$3" meshes="$4" work="$5"
fail() { echo "same_answers_at_every_cpu_level: FAIL: $1" >&2; exit 1; }
mesh="$meshes/cow.off"
if [[ ! -f "$mesh" ]]; then
  [[ "${CI:-}" == "true" ]] && fail "$mesh missing (run scripts/fetch_meshes.sh): a missing prerequisite fails in CI"
  echo "SKIPPED: $mesh missing (run scripts/fetch_meshes.sh)"
  exit 0
fi
setting=auto
[[ "$level" == "x86-64-v3" ]] && setting=x86-64
rm -rf "$work" && mkdir -p "$work"
cmake -S "$src" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DPD_CPU_LEVEL="$setting" \
      -DBUILD_TESTING=OFF >"$work/configure.log" 2>&1 || { cat "$work/configure.log"; fail "configuring at PD_CPU_LEVEL=$setting failed"; }
other=$(sed -n "s/^-- PD_CPU_LEVEL: $setting -> //p" "$work/configure.log")
[[ -n "$other" ]] || fail "the second build's configure log does not say which level PD_CPU_LEVEL=$setting resolved to"
cmake --build "$work/build" --target pd_query -j2 >"$work/build.log" 2>&1 ||
  { tail -50 "$work/build.log"; fail "building pd_query at $other failed"; }
other_query="$work/build/bin/pd_query"
[[ "$other" == "default" ]] || grep -q -- "-march=$other" "$work/build/compile_commands.json" || fail "the second build was not compiled with -march=$other"

# The cow against itself (bounding radius 0.1 m at scale 0.19): 24 cold
# poses near the scene's, random orientations; a coherent path of 400 poses
# sliding through it while turning.
awk 'BEGIN { srand(20261129);
  for (i = 0; i < 24; ++i) {
    do { qw = 2*rand()-1; qx = 2*rand()-1; qy = 2*rand()-1; qz = 2*rand()-1; n = qw*qw+qx*qx+qy*qy+qz*qz } while (n < 0.01 || n > 1);
    n = sqrt(n);
    printf "%.9f %.9f %.9f %.12f %.12f %.12f %.12f\n", 0.1*rand()-0.05, 0.1*rand()-0.05, 0.1*rand()-0.05, qw/n, qx/n, qy/n, qz/n } }' >"$work/cold.txt"
awk 'BEGIN { for (i = 0; i < 400; ++i) { t = i / 399.0; a = 0.5 * t;
  printf "%.9f 0.01 0.005 %.12f 0 %.12f %.12f\n", -0.12 + 0.24 * t, cos(a), 0.6 * sin(a), 0.8 * sin(a) } }' >"$work/path.txt"

run() {  # run BINARY INPUT OUT [--coherent]: the answers without the timings
  "$1" --probe-scale 0.19 --scene-scale 0.19 "${@:4}" "$mesh" "$mesh" <"$2" |
    sed -E 's/,?"(time_us|list_build_us)":[^,}]*//g' >"$3"
}
run "$pd_query" "$work/cold.txt" "$work/cold_main.jsonl"
run "$other_query" "$work/cold.txt" "$work/cold_other.jsonl"
run "$pd_query" "$work/path.txt" "$work/path_main.jsonl" --coherent
run "$other_query" "$work/path.txt" "$work/path_other.jsonl" --coherent
cold_hits=$(grep -c '"collision":true' "$work/cold_main.jsonl" || true)
path_hits=$(grep -c '"collision":true' "$work/path_main.jsonl" || true)
(( cold_hits >= 20 )) || fail "only $cold_hits of 24 cold poses collide: the comparison would say little"
(( path_hits >= 200 )) || fail "only $path_hits of 400 path poses collide: the comparison would say little"
for kind in cold path; do
  if ! cmp -s "$work/${kind}_main.jsonl" "$work/${kind}_other.jsonl"; then
    # (diff exits 1 on a difference: not the end of this script under set -e)
    diff "$work/${kind}_main.jsonl" "$work/${kind}_other.jsonl" | head -6 >&2 || true
    fail "$kind answers differ between $level and $other"
  fi
done
[[ "$level" == "$other" ]] && note=" (one level on this machine: two $level builds)" || note=""
echo "same_answers_at_every_cpu_level: PASS: $level and $other give the same answers and work on $cold_hits cold and $path_hits coherent colliding cow-cow queries$note"
