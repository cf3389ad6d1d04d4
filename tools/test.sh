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
