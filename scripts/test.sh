#!/usr/bin/env bash
# The test command: set-up (packages + assets), build, and every test (unit + differential vs lavapipe), then the
# sanitizer build (AddressSanitizer + UBSan: the unit suite, a differential subset) and the fuzz build (clang, libFuzzer
# targets of the input parsers, bounded).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
# Each phase's wall time, printed as it ends and summed at the end (CI's budget is 25 minutes on 2 cores).
phase_start=$SECONDS phases=""
phase() { phases="$phases$1 $((SECONDS - phase_start)) s; "; echo "test.sh: $1 took $((SECONDS - phase_start)) s"; phase_start=$SECONDS; }
bash scripts/setup.sh
phase setup
# Transparent huge pages for glibc's heap (and the Vulkan drivers', which allocate through it): on the VMs CI and this
# project run on, a page fault costs microseconds, and a verify frame touches ~1 GB of fresh memory (16 shadow maps of
# 1024², their array textures, readbacks): 200,000 faults become 20,000 and the frame runs 2-3x faster (RESULTS,
# "Session 34"). No bit changes: only where the memory comes from.
export GLIBC_TUNABLES=${GLIBC_TUNABLES:+$GLIBC_TUNABLES:}glibc.malloc.hugetlb=1
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
phase "release build"
(cd build && ctest --output-on-failure -j"$(nproc)")
phase "release tests"
# The sanitizer build (issue 20): its own folder, only what its tests need (no benchmarks, no long verify suites).
# Every report is fatal; leaks inside libraries are suppressed by name (tests/lsan.supp).
cmake -S . -B build-san -G Ninja -DCMAKE_BUILD_TYPE=Release -DSHADETWIN_SANITIZE=ON
cmake --build build-san -j"$(nproc)"
phase "sanitizer build"
# (No detect_stack_use_after_return: GCC 12's fake stack frames do not keep the 32-byte alignment of the SIMD lane
# types, and an aligned AVX load of one faults: seen in philox4x32, x8 build.)
export ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1
export LSAN_OPTIONS=suppressions=$root/tests/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# The slowest unit tests under ASan (2-20 min each, the glints kernel's convergence sweeps and the counted frames of the
# largest scenes) run in the release build above only; their code paths run here through the faster tests beside them.
# (A negative GoogleTest filter: each ctest is a whole test executable, CMakeLists.txt add_unit_test.)
san_skip='ShadeGlints.FlatMap*:ShadeGlints.KernelAgrees*:ShadeGlints.HardCases*:ShadeGlints.RotatedLobe*:PassCounts.AbsentBrdfKinds*'
san_skip="$san_skip:*PassCountsCoverage*glints_torus*:*PassCountsCoverage*contact*:*PassCountsCoverage*textured*:*Determinism*glints*"
(cd build-san && GTEST_FILTER="-$san_skip" ctest --output-on-failure -j"$(nproc)")
phase "sanitizer tests"
# The fuzz build (issue 20): libFuzzer targets of the input parsers (clang 14), each for a bounded time from the shipped
# files, every seed and regression input once.
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ -DSHADETWIN_FUZZ=ON
cmake --build build-fuzz -j"$(nproc)"
phase "fuzz build"
(cd build-fuzz && ctest --output-on-failure -j"$(nproc)")
phase "fuzz tests"
echo "test.sh: $phases${SECONDS} s in all"
