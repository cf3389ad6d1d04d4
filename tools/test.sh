#!/usr/bin/env bash
# Quick start 2: set up, build, and run every test (unit, scenario, image, command line).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh
export GALLIUM_DRIVER=llvmpipe
ctest --test-dir build --output-on-failure -j2 --timeout 600
