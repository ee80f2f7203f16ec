#!/usr/bin/env bash
# From a fresh Debian 12 clone to the whole default test suite: install the packages, build in
# Release with warnings as errors (configured as scripts/quickstart.sh does, so the two share
# one build), run CTest (everything but the on-demand `slow` label), then build with
# AddressSanitizer + UBSan and run the unit tests again (not the end-to-end runs of the command
# line, label end_to_end, which take minutes there, nor the distributed tests again on 3 ranks,
# label ranks_variant, which the 2-rank entry checks there).
#   scripts/test.sh            default suite
#   RBCFLOW_TEST_LABELS=slow scripts/test.sh      also the long validations (hours)
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
jobs=$(nproc)

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRBCFLOW_WERROR=ON
cmake --build build -j "$jobs"

# VTK renders only through X: tests run under a virtual display (see docs/rendering.md).
run_ctest() { xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest "$@"; }

if [ "${RBCFLOW_TEST_LABELS:-}" = "slow" ]; then
  run_ctest --test-dir build --output-on-failure --no-tests=error -j "$jobs"
else
  run_ctest --test-dir build --output-on-failure --no-tests=error -j "$jobs" -LE slow
fi

if [ "${RBCFLOW_SKIP_SANITIZERS:-0}" != "1" ]; then
  # Warnings are checked (as errors) by the Release build above; sanitizer instrumentation
  # makes GCC raise false positives of its own, so they are not errors here.
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRBCFLOW_SANITIZE=ON \
        -DRBCFLOW_WERROR=OFF -DRBCFLOW_BUILD_BENCH=OFF
  cmake --build build-asan -j "$jobs" --target unit_tests
  # Leaks inside third-party libraries (gmsh) are suppressed by tests/lsan.supp.
  (
    export ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp"
    export UBSAN_OPTIONS=print_stacktrace=1
    run_ctest --test-dir build-asan --output-on-failure --no-tests=error -j "$jobs" -L unit -LE "end_to_end|ranks_variant"
  )
fi
