#!/usr/bin/env bash
# When no private network namespace can be made (here: `unshare` is not on
# PATH), scripts/netns_run.sh must not run the command and must exit 125
# (CTest: skipped) on a developer machine, but 1 (failed) under CI=true, so
# that a skip cannot hide a missing install step in CI.
#   netns_ci_selftest.sh NETNS_RUN WORK_DIR
set -euo pipefail
netns_run="$1" work="$2"
rm -rf "$work" && mkdir -p "$work/bin"
bash_path=$(command -v bash)
failures=0
check() {  # check WANT_EXIT CI_VALUE
  local want="$1" ci="$2" got=0
  env -i PATH="$work/bin" CI="$ci" "$bash_path" "$netns_run" "$bash_path" -c "echo ran >'$work/ran'" \
    >"$work/out" 2>&1 || got=$?
  if [[ "$got" == "$want" && ! -e "$work/ran" ]]; then
    echo "ok   CI='$ci': exit $got, command not run"
  else
    echo "FAIL CI='$ci': exit $got (expected $want), command run: $([[ -e "$work/ran" ]] && echo yes || echo no)"
    sed 's/^/     /' "$work/out"
    failures=$((failures + 1))
  fi
  rm -f "$work/ran"
}
check 125 ""
check 125 false
check 1 true
check 1 1
((failures == 0)) && echo "netns_ci_selftest: PASS" || { echo "netns_ci_selftest: $failures FAILED"; exit 1; }
