#!/usr/bin/env bash
# Builds every test (and the volprep/volrender executables the CLI tests run) with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer into build-asan/ and runs the whole CTest suite under them, leak checking on.
# Any sanitizer report fails its test. Prints the build and test times.
# Usage: scripts/sanitize.sh [CTEST_ARGS...]   (e.g. -R '^Load' to run a part; -E Vulkan to leave the GPU tests out)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh clang libclang-rt-14-dev  # libclang-rt-14-dev: the sanitizer runtimes

# Also set while building: gtest_discover_tests runs each test binary at build time.
# Leaks inside Mesa's lavapipe, VTK and OpenVDB (system libraries, not ours) are suppressed by fuzz/lsan.supp.
export ASAN_OPTIONS=detect_leaks=1:detect_stack_use_after_return=1
export LSAN_OPTIONS=suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

start=$(date +%s)
CC=clang CXX=clang++ cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVR_SANITIZE=ON >/dev/null
# The tests and what they run (volprep, volrender); benchmarks (and their short CTest runs, label bench) are left
# out: timing sanitized code tells nothing.
tests=$(cmake --build build-asan --target help | grep -o '^[a-z0-9_]*_test' | sort -u)
cmake --build build-asan -j "$(nproc)" --target $tests
built=$(date +%s)
cd build-asan
status=0
# The Vulkan loader unloads Mesa's lavapipe driver before LeakSanitizer looks, which then sees the driver's global
# allocations as leaked from an "<unknown module>". Preloading the driver keeps it mapped (and them reachable).
lavapipe=$(find /usr/lib -name libvulkan_lvp.so -print -quit)
LD_PRELOAD=$lavapipe ctest --output-on-failure -j "$(nproc)" --timeout 900 -LE bench "$@" || status=$?
echo "sanitize.sh: build $((built - start)) s, tests $(($(date +%s) - built)) s"
exit $status
