#!/usr/bin/env bash
# Quick check of scripts/soak.sh (about 20 s): runs it for one 14 s trajectory
# with a 1 s memory sample (no cyclictest floor) and checks its report and
# verdict: numeric memory, miss and pose figures, at least 10 memory samples,
# and a verdict that follows from the judged figures (PASS and exit 0 exactly
# when RSS growth <= 1024 kB, zero compute-caused misses, zero lost poses and
# zero non-finite wrenches; otherwise FAIL, exit 1, naming each failed one).
#   run_soak_quick.sh BIN_DIR WORK_DIR
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
bin="$1" work="$2"
rm -rf "$work" && mkdir -p "$work"
rc=0
"$ROOT/scripts/soak.sh" --seconds 10 --sample-s 1 --floor-s 0 --bin-dir "$bin" --out "$work/soak" || rc=$?
# 125: no private network namespace (skipped; under CI=true netns_run exits 1).
((rc == 125)) && exit 125
md="$work/soak.md" csv="$work/soak.csv"
fail() { echo "run_soak_quick: FAIL: $1"; exit 1; }
[[ -s "$md" ]] || fail "soak.sh exited $rc without a report"
row() { grep -E "^\| $1 " "$md" | head -n 1; }
grep -Eq '^\| server RSS start / after warm-up / end / max \| [0-9]+ / [0-9]+ / [0-9]+ / [0-9]+ kB \|' "$md" ||
  fail "memory figures missing"
growth=$(row 'RSS growth after warm-up' | sed -En 's/.*\| (-?[0-9]+) kB \(.*/\1/p')
compute=$(row 'compute-caused misses' | sed -En 's/.*\| ([0-9]+) \|$/\1/p')
late=$(row 'late wake-up misses' | sed -En 's/.*\| ([0-9]+) \(.*/\1/p')
read -r sent lost superseded < <(row 'poses sent' | sed -En 's/.*\| ([0-9]+) \/ ([0-9]+) \/ ([0-9]+) \|$/\1 \2 \3/p')
nonfinite=$(row 'non-finite wrenches' | sed -En 's/.*\| ([0-9]+) \|$/\1/p')
for v in growth compute late sent lost superseded nonfinite; do
  [[ -n "${!v:-}" ]] || fail "no number for '$v' in $md"
done
grep -Eq '^\| ticks / deadline misses \| [0-9]+ / [0-9]+ ' "$md" || fail "deadline misses missing"
rows=$(($(wc -l <"$csv") - 1))
((rows >= 10)) || fail "only $rows memory samples in $csv"
awk -F, 'NR > 1 && !($1 ~ /^[0-9.]+$/ && $2 ~ /^[0-9]+$/) { bad = 1 } END { exit bad }' "$csv" || fail "malformed rows in $csv"

# The verdict follows from the judged figures.
verdict=$(row verdict)
expected=()
((growth <= 1024)) || expected+=("RSS grew")
((compute == 0)) || expected+=("compute-caused misses")
((lost == 0)) || expected+=("poses lost")
((nonfinite == 0)) || expected+=("non-finite wrenches")
if ((${#expected[@]} == 0)); then
  [[ "$verdict" == "| verdict | PASS |" && $rc -eq 0 ]] ||
    fail "every judged figure is within its limit but the verdict is '$verdict' (exit $rc)"
else
  [[ "$verdict" == "| verdict | FAIL"* && $rc -eq 1 ]] || fail "expected FAIL (exit 1), got '$verdict' (exit $rc)"
  for e in "${expected[@]}"; do
    [[ "$verdict" == *"$e"* ]] || fail "the verdict does not name '$e': $verdict"
  done
fi
verdict_text=${verdict#| verdict | }
echo "run_soak_quick: PASS (soak verdict: ${verdict_text% |}; $rows memory samples; growth $growth kB," \
     "compute-caused misses $compute, late wake-up misses $late)"
