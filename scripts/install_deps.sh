#!/usr/bin/env bash
# Installs every Debian 12 package the project needs (idempotent). Needs root.
set -euo pipefail
PKGS=(
  build-essential cmake pkg-config git
  libeigen3-dev libfcl-dev libccd-dev libassimp-dev
  liblcm-dev liblcm-bin libspdlog-dev libfmt-dev
  libgtest-dev libgmock-dev
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev zlib1g-dev
  gnuplot-nox
  libcgal-demo assimp-testmodels
  iproute2 util-linux jq
  rt-tests  # cyclictest: the platform's late wake-up floor beside the loop benchmark and the soak
  clang libclang-rt-14-dev  # scripts/fuzz.sh: libFuzzer
  libjs-three chromium libpng-dev  # session viewer page (three.js), its browser test, png_stats
)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  SUDO=""; [[ $(id -u) -ne 0 ]] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi
echo "install_deps: all ${#PKGS[@]} packages present"
