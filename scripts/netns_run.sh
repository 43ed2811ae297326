#!/usr/bin/env bash
# Runs a command in a private network namespace that has only loopback, with
# the multicast route LCM's udpm provider needs, so that no packet can leave
# the machine:  scripts/netns_run.sh CMD [ARGS...]
# As root this is `unshare -n`; otherwise a user namespace maps the caller to
# root first (`unshare -r -n`). If no namespace can be made the command is
# NOT run: udpm on the host network could send multicast off the machine.
# Exit 125 then (CTest reads it as "skipped"), except under CI (CI set and not
# "", 0 or false): there a missing prerequisite fails, exit 1, so that a
# skip cannot hide a missing install step.
set -euo pipefail

if (($# == 0)); then
  echo "usage: $(basename "$0") CMD [ARGS...]   (runs CMD in a private network namespace)" >&2
  exit 2
fi

command_text="$*"
case "${CI:-}" in
  ""|0|false|False|FALSE) no_namespace_exit=125 ;;
  *) no_namespace_exit=1 ;;
esac
export PD_NO_NAMESPACE_EXIT=$no_namespace_exit
refuse() {
  echo "netns_run: $1" >&2
  echo "netns_run: refusing to run '${command_text}' without a private network namespace: LCM udpm" \
       "multicast on the host network could leave the machine." >&2
  ((no_namespace_exit == 125)) || echo "netns_run: CI=${CI}: a missing network namespace fails here (not skipped)" >&2
  exit "$no_namespace_exit"
}

command -v unshare >/dev/null 2>&1 || refuse "'unshare' not found (Debian package util-linux)."
command -v ip >/dev/null 2>&1 || refuse "'ip' not found (Debian package iproute2)."

flags=(--net)
if [[ $(id -u) -ne 0 ]]; then flags=(--map-root-user --net); fi
# Try first so that a refusal gets a clear message rather than unshare's.
if ! err=$(unshare "${flags[@]}" true 2>&1); then
  refuse "cannot create a network namespace (unshare ${flags[*]}: ${err}). Run as root or enable unprivileged user namespaces."
fi

# Inside: bring up lo and route all multicast (224.0.0.0/4) through it; any
# failure stops before the command runs. "$@" keeps the arguments intact.
exec unshare "${flags[@]}" sh -c '
  ip link set lo up && ip route add 224.0.0.0/4 dev lo || {
    echo "netns_run: could not set up loopback multicast in the namespace" >&2; exit "$PD_NO_NAMESPACE_EXIT"; }
  exec "$@"' netns_run "$@"
