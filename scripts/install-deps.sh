#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Installs every Debian 12 package railtab needs to build, test and chart.
# Safe to run twice; needs root (or sudo) for apt-get.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev            # linear algebra (core)
  libfftw3-dev             # FFT of the half-space convolutions (src/halfspace)
  libtbb-dev               # oneTBB parallel sweep (generator)
  libhdf5-dev hdf5-tools   # table files; h5dump for inspection
  libgtest-dev libgmock-dev
  libbenchmark-dev         # Google Benchmark
  libcli11-dev             # command line
  libtomlplusplus-dev      # scene files
  nlohmann-json3-dev       # JSON output of railtab eval
  libfmt-dev               # formatting
  openmpi-bin libopenmpi-dev  # MPI table generation (mpirun -n N railtab generate)
  gnuplot-nox              # PNG charts from CSV (pngcairo)
  python3-dev python3-pybind11   # the Python module railtab (python/)
  python3-numpy python3-pytest   # its arrays and its tests
  python3-xarray python3-h5netcdf python3-netcdf4 python3-h5py  # query results as Datasets; tables opened by xarray and h5py (tests)
  clang-14 llvm-14         # sanitizer and fuzz builds of CI (.ci/run: sanitize, tsan, fuzz); llvm-symbolizer for their stacks
  libclang-rt-14-dev       # clang 14's runtimes: ASan, UBSan, TSan and libFuzzer (libclang_rt.fuzzer-x86_64.a)
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
