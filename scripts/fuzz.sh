#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan, -DPD_FUZZ=ON) and runs
# each for a bounded time, starting from its seed corpus:
#
#   scripts/fuzz.sh [--seconds N] [--build-dir DIR] [--jobs J] [TARGET...]
#
#   --seconds N    per target (default 60), libFuzzer -max_total_time
#   --build-dir D  clang build tree (default build-fuzz/)
#   TARGET         load_mesh, scene_config, pose_message (default: all three)
#
# New corpus entries go to DIR/corpus/<target>/ (the committed seeds in
# tests/fuzz/corpus/ are only read). Every crash, leak, timeout or OOM input is
# copied to tests/fuzz/regressions/<target>/, where the normal test suite
# replays it (ctest -R fuzz_regress); the script then exits 1. No network.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
seconds=60 build="$ROOT/build-fuzz" jobs="$(nproc)" targets=()
while (($#)); do
  case "$1" in
    --seconds) seconds="$2"; shift 2 ;;
    --build-dir) build="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    -*) echo "fuzz.sh: unknown option '$1'" >&2; exit 2 ;;
    *) targets+=("$1"); shift ;;
  esac
done
((${#targets[@]})) || targets=(load_mesh scene_config pose_message)
[[ "$seconds" =~ ^[0-9]+$ && "$seconds" -gt 0 ]] || { echo "fuzz.sh: --seconds must be a positive integer, got '$seconds'" >&2; exit 2; }
for t in "${targets[@]}"; do
  [[ -d "$ROOT/tests/fuzz/corpus/$t" ]] || { echo "fuzz.sh: unknown target '$t'" >&2; exit 2; }
done

"$ROOT/scripts/install_deps.sh" >/dev/null
CXX=clang++ cmake -S "$ROOT" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPD_FUZZ=ON >/dev/null
cmake --build "$build" -j"$jobs" --target "${targets[@]/#/fuzz_}"

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}"
# assimp 5.2 itself leaks a few kB when its STL reader throws on some
# malformed files (kept as tests/fuzz/regressions/load_mesh/leak-*; a mesh is
# loaded once at start-up): leaks allocated inside libassimp are suppressed,
# leaks anywhere else still fail.
printf 'leak:libassimp.so\n' >"$build/lsan.supp"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$build/lsan.supp}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
found=0
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t" artifacts="$build/artifacts/$t"
  mkdir -p "$corpus" "$artifacts"
  log="$build/fuzz_$t.log"
  echo "fuzz.sh: fuzz_$t for ${seconds}s (log $log)"
  set +e
  (cd "$build" && TMPDIR="$build" "$build/bin/fuzz_$t" -max_total_time="$seconds" -timeout=20 \
      -rss_limit_mb=2048 -max_len=4096 -print_final_stats=1 -artifact_prefix="$artifacts/" \
      "$corpus" "$ROOT/tests/fuzz/corpus/$t") >"$log" 2>&1
  rc=$?
  set -e
  grep -E '^(stat::number_of_executed_runs|stat::peak_rss_mb)|^#[0-9]+ +DONE' "$log" | sed "s/^/  $t: /" || true
  shopt -s nullglob
  crashes=("$artifacts"/crash-* "$artifacts"/leak-* "$artifacts"/timeout-* "$artifacts"/oom-*)
  shopt -u nullglob
  if ((${#crashes[@]})) || ((rc != 0)); then
    mkdir -p "$ROOT/tests/fuzz/regressions/$t"
    for c in "${crashes[@]}"; do cp "$c" "$ROOT/tests/fuzz/regressions/$t/"; done
    echo "fuzz.sh: FAIL: fuzz_$t exited $rc with ${#crashes[@]} crash input(s), kept in tests/fuzz/regressions/$t/:"
    grep -E 'ERROR|violation|SUMMARY|runtime error' "$log" | head -5 | sed 's/^/    /'
    found=$((found + 1))
  else
    echo "fuzz.sh: fuzz_$t: no crash in ${seconds}s"
  fi
  rm -rf "$artifacts"
done
((found == 0)) && echo "fuzz.sh: PASS (${#targets[@]} targets, ${seconds}s each)" || { echo "fuzz.sh: $found target(s) found crashes"; exit 1; }
