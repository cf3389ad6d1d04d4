#!/usr/bin/env bash
# Quick start 1: set up, build, and run the default scene; results under out/default/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh
export GALLIUM_DRIVER=llvmpipe
./build/sim/vmt run scenes/default.yaml --out out/default
