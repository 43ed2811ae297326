#!/usr/bin/env bash
# Quick check of scripts/soak.sh (about 20 s): runs it for one 14 s trajectory with a 1 s
# memory sample and checks that its report parses: a PASS verdict, numeric
# memory and deadline-miss figures, and at least 10 memory samples.
#   run_soak_quick.sh BIN_DIR WORK_DIR
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
bin="$1" work="$2"
rm -rf "$work" && mkdir -p "$work"
"$ROOT/scripts/soak.sh" --seconds 10 --sample-s 1 --bin-dir "$bin" --out "$work/soak"
md="$work/soak.md" csv="$work/soak.csv"
fail() { echo "run_soak_quick: FAIL: $1"; exit 1; }
grep -q '^| verdict | PASS' "$md" || fail "no PASS verdict in $md"
grep -Eq '^\| server RSS start / after warm-up / end / max \| [0-9]+ / [0-9]+ / [0-9]+ / [0-9]+ kB \|' "$md" ||
  fail "memory figures missing"
grep -Eq '^\| ticks / deadline misses \| [0-9]+ / [0-9]+ ' "$md" || fail "deadline misses missing"
grep -Eq '^\| poses sent / lost / superseded \| [0-9]+ / 0 / [0-9]+ \|' "$md" || fail "pose counts missing"
rows=$(($(wc -l <"$csv") - 1))
((rows >= 10)) || fail "only $rows memory samples in $csv"
awk -F, 'NR > 1 && !($1 ~ /^[0-9.]+$/ && $2 ~ /^[0-9]+$/) { bad = 1 } END { exit bad }' "$csv" || fail "malformed rows in $csv"
echo "run_soak_quick: PASS ($rows memory samples)"
