#!/usr/bin/env bash
# Installs every Debian package bcot needs to build, test and benchmark.
# Idempotent and non-interactive; nothing else is downloaded at build or run time.
#   scripts/setup.sh                 # build, test and benchmark packages
#   scripts/setup.sh --with-blender  # also Blender (Cycles, headless), NumPy and OpenCV for the
#                                    # physically based render path (scripts/pbr_synth.sh,
#                                    # scripts/bench_pbr.sh); not needed for demo.sh / test.sh
set -euo pipefail

with_blender=0
for arg in "$@"; do
  case "$arg" in
    --with-blender) with_blender=1 ;;
    -h|--help) sed -n '2,7p' "$0"; exit 0 ;;
    *) echo "setup: unknown option $arg" >&2; exit 2 ;;
  esac
done

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libceres-dev libsuitesparse-dev
  libopencv-dev libjpeg-dev   # libjpeg-dev: libjpeg-turbo, for the direct JPEG decode
  libassimp-dev libembree-dev
  libaravis-dev libusb-1.0-0-dev aravis-tools aravis-tools-cli
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libfmt-dev libspdlog-dev libtbb-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcpp-httplib-dev   # the local web server of `bcot review`
  libjs-dygraphs       # its charts (embedded into the binary at build time)
  clang libclang-rt-14-dev   # libFuzzer harnesses of the parsers (scripts/fuzz.sh, ctest -L fuzz)
  chromium   # headless renders of the HTML reports in the tests labelled `browser`
)
if [ "$with_blender" -eq 1 ]; then
  packages+=(blender python3-numpy python3-opencv)
fi

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
