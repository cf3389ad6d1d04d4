#!/usr/bin/env bash
# Quick start 2: set up, build, and run every test (unit, scenario, image, command line), first
# on the Release build, then once more under AddressSanitizer + UndefinedBehaviorSanitizer.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh
export GALLIUM_DRIVER=llvmpipe
ctest --test-dir build --output-on-failure -j2 --timeout 600

werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
cmake --preset asan -DVMT_WERROR=$werror >/dev/null
cmake --build build-asan
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizer.supp"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# The sanitizers look for memory and undefined-behaviour faults: every scene runs under them on
# its own backend (both backends are some scene's own), so the scenes' second runs on the other
# backend (label other_backend, digest checks the Release run makes) are left out here.
ctest --test-dir build-asan --output-on-failure -j2 --timeout 900 -LE other_backend

# The libFuzzer targets (tests/fuzz: scene and machine files, NC programs run, Modbus requests,
# the station's HTTP API) in a clang build of their own, each run for seconds from its corpus
# with a fixed seed: a smoke test of the targets and their corpora (docs/testing.md has the
# long runs). Only the targets are built, not the tests of the other builds.
cmake --preset fuzz -DVMT_WERROR=$werror >/dev/null
cmake --build build-fuzz --target fuzz_targets
ctest --test-dir build-fuzz --output-on-failure -j2 -L fuzz
