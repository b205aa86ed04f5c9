#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Configures build/asan (once) and builds the given targets in it. build/asan is ONE clang build
# shared by the sanitizer unit tests (scripts/sanitize.sh asan) and the fuzz targets
# (scripts/fuzz.sh), so CI compiles the libraries once for both:
#   -fsanitize=address,undefined      ASan + UBSan on every object, railtab's and the tests'
#   -fno-sanitize-recover=all          a UBSan report ends the process (exit != 0): CI fails
#   -fsanitize=fuzzer-no-link          libFuzzer's coverage hooks (needed by the fuzz targets;
#                                      in the test programs they cost speed only: the ASan
#                                      runtime has do-nothing defaults for them)
#   -O1 -gline-tables-only             ~2x faster to compile than -O2 -g, still readable stacks
#   -fsized-deallocation               clang 14 leaves C++14 sized delete off (lookup uses it)
#   -fno-sanitize=pointer-overflow     on the lookup's kernel files only (RAILTAB_LOOKUP_KERNEL_OPTIONS:
#                                      interpolate_*, block_gradient, fast_path): UBSan's check of
#                                      their record-pointer arithmetic was most of their compile
#                                      time (block_gradient.cpp about 125 -> 22 s CPU, the linear AVX2
#                                      kernels 109 -> 64 s). It catches only arithmetic that wraps
#                                      the address space or offsets a null pointer; ASan still
#                                      checks every access through those pointers, and every other
#                                      UBSan check stays on them
# Benchmarks, Python, MPI and the shared lookup library are off: not what this build checks.
# Usage: bash scripts/asan_build.sh TARGET...
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -gt 0 ] || { echo "usage: asan_build.sh TARGET..." >&2; exit 2; }
flags="-fsanitize=address,undefined,fuzzer-no-link -fno-sanitize-recover=all -fno-omit-frame-pointer -fsized-deallocation"
mkdir -p build
if [ ! -f build/asan/CMakeCache.txt ]; then
  CC=clang-14 CXX=clang++-14 cmake -S . -B build/asan -G Ninja -DCMAKE_BUILD_TYPE=Debug \
    -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
    -DCMAKE_C_FLAGS_DEBUG="-O1 -gline-tables-only" -DCMAKE_CXX_FLAGS_DEBUG="-O1 -gline-tables-only" \
    -DRAILTAB_BUILD_FUZZ=ON -DRAILTAB_BUILD_TESTS=ON -DRAILTAB_BUILD_BENCH=OFF \
    -DRAILTAB_BUILD_PYTHON=OFF -DRAILTAB_MPI=OFF -DRAILTAB_LOOKUP_SHARED=OFF \
    -DRAILTAB_LOOKUP_KERNEL_OPTIONS=-fno-sanitize=pointer-overflow > build/asan-configure.log
fi
cmake --build build/asan --parallel "$(nproc)" --target "$@"
