#!/usr/bin/env bash
# Quick start 2: set up, build and run every test (unit, scenario, image, command line) on the
# Release build; then the sanitizer pass.
#
# The sanitizer pass is one clang build with AddressSanitizer + UndefinedBehaviorSanitizer and
# libFuzzer's coverage (preset `fuzz`) of vmt and the fuzz targets only: it runs every scene on
# its own backend and the command-line tests of hostile input (label `sanitize`) with that vmt,
# then each fuzz target for seconds from its corpus with a fixed seed. Building the ~190 test
# executables a second time under the sanitizers took longer than a 2-core CI allows; that
# fuller pass is `tools/test.sh --all-sanitized` (docs/testing.md).
set -euo pipefail
cd "$(dirname "$0")/.."
all_sanitized=false
case "${1:-}" in
  "") ;;
  --all-sanitized) all_sanitized=true ;;
  *) echo "usage: tools/test.sh [--all-sanitized]" >&2; exit 2 ;;
esac

bash tools/build.sh
export GALLIUM_DRIVER=llvmpipe
ctest --test-dir build --output-on-failure -j2 --timeout 600

werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizer.supp"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
cmake --preset fuzz -DVMT_WERROR=$werror >/dev/null
cmake --build build-fuzz --target fuzz_targets vmt
ctest --test-dir build-fuzz --output-on-failure -j2 --timeout 900 -L 'sanitize|fuzz'

if $all_sanitized; then
  # Every test of the Release run again in a gcc sanitizer build; the scenes' second runs on the
  # other backend (label other_backend, digest checks the Release run makes) are left out.
  cmake --preset asan -DVMT_WERROR=$werror >/dev/null
  cmake --build build-asan
  ctest --test-dir build-asan --output-on-failure -j2 --timeout 900 -LE other_backend
fi
