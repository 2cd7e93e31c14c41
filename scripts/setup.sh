#!/usr/bin/env bash
# Installs every Debian package bcot needs to build, test and benchmark.
# Idempotent and non-interactive; nothing else is downloaded at build or run time.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libceres-dev libsuitesparse-dev
  libopencv-dev
  libassimp-dev libembree-dev
  libaravis-dev libusb-1.0-0-dev aravis-tools aravis-tools-cli
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libfmt-dev libspdlog-dev libtbb-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  chromium   # headless renders of the HTML reports in the tests labelled `browser`
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
echo "setup: installing ${missing[*]}"
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "setup: done"
