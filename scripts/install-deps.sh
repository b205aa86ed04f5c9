#!/usr/bin/env bash
# Installs every Debian 12 package railtab needs to build, test and chart.
# Safe to run twice; needs root (or sudo) for apt-get.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev            # linear algebra (core)
  libtbb-dev               # oneTBB parallel sweep (generator)
  libhdf5-dev hdf5-tools   # table files; h5dump for inspection
  libgtest-dev libgmock-dev
  libbenchmark-dev         # Google Benchmark
  libcli11-dev             # command line
  libtomlplusplus-dev      # scene files
  nlohmann-json3-dev       # JSON output of railtab eval
  libfmt-dev               # formatting
  gnuplot-nox              # PNG charts from CSV (pngcairo)
  clang-14 libclang-rt-14-dev llvm-14  # libFuzzer targets and sanitizer runtimes (.ci/run, scripts/fuzz.sh)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
