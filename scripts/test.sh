#!/usr/bin/env bash
# The test command: set-up (packages + assets), build, and every test (unit + differential vs lavapipe), then the
# sanitizer build (clang, AddressSanitizer + UBSan: the unit suite, a differential subset, the bounded fuzzers).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bash scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
(cd build && ctest --output-on-failure -j"$(nproc)")
# The sanitizer build (issue 20): its own folder, only what its tests need (no benchmarks, no long verify suites).
# Every report is fatal; leaks in the Vulkan drivers' own allocations are suppressed by name (tests/lsan.supp).
cmake -S . -B build-san -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ -DSHADETWIN_SANITIZE=ON
cmake --build build-san -j"$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1
export LSAN_OPTIONS=suppressions=$root/tests/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
(cd build-san && ctest --output-on-failure -j"$(nproc)")
